#!/usr/bin/env bash
# The web view's browser test needs Node.js and npm (Debian's, installed only when the machine
# has no `node` or `npm` command: one from elsewhere, such as NodeSource, is used as it is) and
# chrome-remote-interface from the npm registry, pinned by tests/view/package-lock.json and
# installed into tests/view/node_modules when that is missing or older than the lock.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
updated=0
install() {
  echo "installing: $*"
  if ((!updated)); then $sudo apt-get update; updated=1; fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "$@"
}
# One at a time: a nodejs package that brings its own npm (NodeSource's) must not be paired
# with Debian's npm, which would conflict with it.
command -v node >/dev/null || install nodejs
command -v npm >/dev/null || install npm

view="$root/tests/view"
if [ ! -f "$view/node_modules/.package-lock.json" ] ||
   [ "$view/package-lock.json" -nt "$view/node_modules/.package-lock.json" ]; then
  (cd "$view" && npm ci --no-audit --no-fund)
fi
