#!/usr/bin/env bash
# The web view's browser test needs Node.js and npm (Debian's, installed only when the machine
# has no `node` or `npm` command: one from elsewhere, such as NodeSource, is used as it is) and
# chrome-remote-interface from the npm registry, pinned by tests/view/package-lock.json and
# installed into tests/view/node_modules when that is missing or older than the lock.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

missing=()
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

view="$root/tests/view"
if [ ! -f "$view/node_modules/.package-lock.json" ] ||
   [ "$view/package-lock.json" -nt "$view/node_modules/.package-lock.json" ]; then
  (cd "$view" && npm ci --no-audit --no-fund)
fi
