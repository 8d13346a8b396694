#!/usr/bin/env bash
# Speed against accuracy of igi and the peer comparison (docs/ACCURACY.md): sets up and builds
# (scripts/setup.sh, plus python3-matplotlib and, with --peers, embree-tools and blender), then
# runs scripts/accuracy_report.py, which renders converged references with our path tracer
# (cached in out/reference/, reused when present), sweeps igi's parameters and accumulation,
# compares every image with igi-compare and writes docs/accuracy/ (results.csv, results.md, one
# plot per scene) and the generated blocks of docs/ACCURACY.md.
#
# Usage: scripts/bench_accuracy.sh [--quick] [--peers] [more accuracy_report.py options]
#   --quick   smoke run of a few minutes: default scene, few points, weak reference; the report
#             goes to out/accuracy-quick/report/ and docs/ are not touched
#   --peers   also Blender Cycles (equal-time curves) and the Embree pathtracer probe
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# A full run with --peers took 7.5 minutes on 2 shared cores at 320 x 240 (references included).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

quick=0
peers=0
for a in "$@"; do
  case "$a" in
    --quick) quick=1 ;;
    --peers) peers=1 ;;
  esac
done

extra=(python3-matplotlib openimageio-tools)
if ((peers)); then extra+=(embree-tools blender); fi

if [ -n "${IGI_BUILD:-}" ]; then
  build="$(cd "$IGI_BUILD" && pwd)"
  for p in "${extra[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      echo "missing Debian package $p: run scripts/setup.sh ${extra[*]} (or unset IGI_BUILD)" >&2
      exit 1
    fi
  done
else
  "$root/scripts/setup.sh" "${extra[@]}"
  build="$root/build"
fi

args=(--build "$build" --command "scripts/bench_accuracy.sh $*")
if ((quick)); then
  args+=(--out "$root/out/accuracy-quick" --docs "")
fi
cd "$root"
# Debian's Python: matplotlib comes from python3-matplotlib, not from a pyenv python3 on PATH.
exec /usr/bin/python3 "$root/scripts/accuracy_report.py" "${args[@]}" "$@"
