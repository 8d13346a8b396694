#!/usr/bin/env bash
# Instructions a client spends rendering first frames, counted by callgrind: a figure the
# machine's load does not move (wall-clock runs on a shared VM scatter by 20 % and more), for
# comparing two builds' per-frame work (docs/MATERIALS.md, "The Cornell scenes' first frame").
# Counts only inside TileRenderer::renderChunk (no start-up, no scene build). Valgrind runs
# Embree's AVX2 8-wide kernels whatever the CPU has, and counts each iteration of a `rep`
# string instruction as one instruction (so a build whose clears are rep stos and one whose
# clears are vector loops or libc calls do not compare on those clears).
#
# Usage: scripts/callgrind_frame.sh BIN [scene...] [--frames 4] [--width 320 --height 240]
# BIN is a folder holding igi-bench (a build's bin/). Without scenes: the default scene.
# Prints one line per scene: its name and the instruction count.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="$1"
shift
frames=4 width=320 height=240 scenes=()
while (($#)); do
  case "$1" in
    --frames) frames="$2"; shift 2 ;;
    --width) width="$2"; shift 2 ;;
    --height) height="$2"; shift 2 ;;
    *) scenes+=("$1"); shift ;;
  esac
done
((${#scenes[@]})) || scenes=("$root/scenes/cornell/cornell.json")
command -v valgrind >/dev/null || { echo "callgrind_frame.sh: needs valgrind (apt-get install valgrind)" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# libhwy (OpenImageIO -> libjxl) runs `rdtscp` in a static initializer, which valgrind 3.19
# cannot decode (SIGILL before main). Its TimerResolution() is called through the PLT, so a
# preloaded definition replaces it; nothing here uses hwy's timers.
cat >"$out/nohwy.cpp" <<'CPP'
#include <cstdint>
namespace hwy { namespace platform { std::uint64_t TimerResolution() { return 1; } } }
CPP
c++ -O2 -shared -fPIC -o "$out/nohwy.so" "$out/nohwy.cpp"
for s in "${scenes[@]}"; do
  LD_PRELOAD="$out/nohwy.so" valgrind --tool=callgrind \
    --toggle-collect='igi::TileRenderer::renderChunk*' --callgrind-out-file="$out/cg" \
    "$bin/igi-bench" --scene "$s" --allow-outside-paths --threads 1 --frames "$frames" \
    --segments 10000 --width "$width" --height "$height" >/dev/null 2>"$out/err" ||
    { tail -5 "$out/err" >&2; exit 1; }
  echo "$(basename "$s") $(grep -o 'Collected : [0-9]*' "$out/err" | cut -d' ' -f3) instructions"
done
