# Sourced by the bench scripts: `bench_build PACKAGE...` sets `build` to the build to measure.
# With IGI_BUILD set, that build (its bin/ must hold igi-master, igi-client and igi-compare), once
# the extra Debian packages are checked; otherwise scripts/setup.sh installs what is missing
# (those packages included) and builds build/.
bench_build() {
  local root exe p
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  if [ -n "${IGI_BUILD:-}" ]; then
    if [ ! -d "$IGI_BUILD" ]; then
      echo "IGI_BUILD=$IGI_BUILD is not a folder" >&2
      exit 1
    fi
    build="$(cd "$IGI_BUILD" && pwd)"
    for exe in igi-master igi-client igi-compare; do
      if [ ! -x "$build/bin/$exe" ]; then
        echo "IGI_BUILD=$IGI_BUILD has no bin/$exe: build it first (or unset IGI_BUILD)" >&2
        exit 1
      fi
    done
    for p in "$@"; do
      if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        echo "missing Debian package $p: run scripts/setup.sh $* (or unset IGI_BUILD)" >&2
        exit 1
      fi
    done
  else
    "$root/scripts/setup.sh" "$@"
    build="$root/build"
  fi
}
