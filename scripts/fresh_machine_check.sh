#!/usr/bin/env bash
# The README's two commands on a machine that starts empty: builds a minimal Debian 12 root with
# debootstrap, copies the committed tree into it (git archive HEAD) and runs, in a chroot and
# exactly as the README writes them, scripts/run.sh and then scripts/test.sh. Prints each
# command's exit code and duration, and the first error line of one that fails, whose whole
# output it keeps beside the work folder (/var/tmp/igi-fresh-<time>-<command>.log by default).
#
# Why: CI runs on a machine where everything ever installed is still there, so it cannot see a
# missing install step. This check can. It takes 20-40 minutes on 2 cores, too slow for the test
# command: run it before resolving anything that touches set-up, dependencies or the build.
#
# Usage (as root):
#   scripts/fresh_machine_check.sh [--keep] [--no-shared] [--work-dir DIR] [--cache-dir DIR]
#     --keep        keep the root (unmounted) for a look afterwards; its path is printed
#     --no-shared   do not copy ../shared/scenes beside the tree (tests that read it skip)
#     --work-dir    where the root is made (default: a new folder under /var/tmp)
#     --cache-dir   debootstrap's package cache, kept between runs so that only the first run
#                   downloads the base system (default: /var/cache/igi-fresh-machine-check);
#                   the root itself is made anew every time
#
# The mirror and the apt sources come from this machine's own apt configuration, and the CA
# certificates and npm settings that let it reach its registries from its own; nothing about
# them is written here. Cleanup is a trap: every mount is undone first, and the root is removed
# with rm --one-file-system, so that a mount left behind (a bind-mounted /dev) is never emptied.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
suite=bookworm
keep=0
with_shared=1
work_parent=/var/tmp
cache_dir=/var/cache/igi-fresh-machine-check

while (($#)); do
  case "$1" in
    --keep) keep=1 ;;
    --no-shared) with_shared=0 ;;
    --work-dir) work_parent="$2"; shift ;;
    --cache-dir) cache_dir="$2"; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "fresh_machine_check: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ "$(id -u)" -ne 0 ]; then
  echo "fresh_machine_check: needs root (debootstrap, chroot and mounts); run it as root or with sudo" >&2
  exit 2
fi

# The first Debian archive (not the security one) in this machine's apt sources, deb822 or
# one-line format.
host_mirror() {
  local f line
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk -v suite="$suite" '
      /^[[:space:]]*$/ { if (uris != "" && suites ~ ("(^| )" suite "( |$)")) { print uris; exit }
                         uris = ""; suites = ""; next }
      /^URIs:/   { uris = $2 }
      /^Suites:/ { $1 = ""; suites = $0 }
      END { if (uris != "" && suites ~ ("(^| )" suite "( |$)")) print uris }' "$f"
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    while read -r line; do
      # deb [options] URI SUITE COMPONENTS...
      set -- $line
      [ "${1:-}" = deb ] || continue
      shift
      case "${1:-}" in \[*) while [ $# -gt 0 ] && [[ "$1" != *\] ]]; do shift; done; shift ;; esac
      [ "${2:-}" = "$suite" ] && echo "$1"
    done <"$f"
  done
}
mirror="$(host_mirror | head -n 1)"
if [ -z "$mirror" ]; then
  echo "fresh_machine_check: no '$suite' archive in this machine's apt sources (/etc/apt)" >&2
  exit 2
fi

if ! command -v debootstrap >/dev/null; then
  echo "installing debootstrap"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap
fi

work="$(mktemp -d "$work_parent/igi-fresh.XXXXXX")"
chroot_dir="$work/root"
mounted=()

cleanup() {
  local status=$? i
  # Nothing here may stop the cleanup half-way (a grep that matches nothing fails).
  set +e
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}" 2>/dev/null || true
  done
  # Whatever is still mounted under the root (a mount a build made, say) goes too, deepest first.
  if [ -d "$chroot_dir" ]; then
    findmnt -rn -o TARGET | grep -F "$chroot_dir/" | sort -r | while read -r m; do
      umount -l "$m" 2>/dev/null
    done
  fi
  if findmnt -rn -o TARGET | grep -qF "$work"; then
    echo "fresh_machine_check: something is still mounted under $work; not removing it" >&2
  elif ((keep)); then
    echo "kept the root at $chroot_dir"
  else
    rm -rf --one-file-system "$work"
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

mount_into() {  # mount_into TARGET mount-arguments...
  local target="$chroot_dir$1"
  shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounted+=("$target")
}

elapsed() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }

echo "== debootstrap --variant=minbase $suite from $mirror"
mkdir -p "$cache_dir"
t0=$SECONDS
debootstrap --variant=minbase --cache-dir="$cache_dir" "$suite" "$chroot_dir" "$mirror" \
  >"$work/debootstrap.log" 2>&1 || {
  echo "debootstrap failed; its log:" >&2
  tail -n 20 "$work/debootstrap.log" >&2
  exit 1
}
echo "   done in $(elapsed $((SECONDS - t0)))"

# The machine's own apt set-up (sources, the security and updates suites, Acquire settings), as
# a new machine of this kind would have it; and its resolver.
rm -f "$chroot_dir/etc/apt/sources.list"
cp -a /etc/apt/sources.list.d/. "$chroot_dir/etc/apt/sources.list.d/"
[ -f /etc/apt/sources.list ] && cp /etc/apt/sources.list "$chroot_dir/etc/apt/sources.list"
cp -a /etc/apt/apt.conf.d/. "$chroot_dir/etc/apt/apt.conf.d/"
cp -L /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
# Its trust for the registries it reaches, as a new machine of this kind has it: the local CA
# certificates (an intercepting proxy's, here), which ca-certificates adds to the system bundle
# when the set-up installs it, and npm's global settings (here: use that bundle).
if [ -d /usr/local/share/ca-certificates ]; then
  mkdir -p "$chroot_dir/usr/local/share/ca-certificates"
  cp -a /usr/local/share/ca-certificates/. "$chroot_dir/usr/local/share/ca-certificates/"
fi
[ -f /etc/npmrc ] && cp /etc/npmrc "$chroot_dir/etc/npmrc"

# The root a mount point of its own, as / is on a machine: `ip netns` (the LAN tests) makes /
# a slave mount, which fails on a plain folder. First, so that every mount below lies on it.
mount_into "" --bind "$chroot_dir"
mount_into /proc -t proc proc
mount_into /sys -t sysfs sysfs
# The cgroup hierarchy, as a booted Debian has it: slurmd will not start without it.
# (a slave: nothing done to it in the root reaches this machine's).
mount_into /sys/fs/cgroup --rbind /sys/fs/cgroup
mount --make-rslave "$chroot_dir/sys/fs/cgroup"
mount_into /dev --bind /dev
mount_into /dev/pts -t devpts devpts
mount_into /dev/shm -t tmpfs tmpfs
mount_into /tmp -t tmpfs tmpfs

# The committed tree, as a clone would give it, at /work/igi; the shared scenes beside it, where
# the tests look for them (../shared/scenes).
echo "== the tree: git archive $(git -C "$repo" rev-parse --short HEAD)"
mkdir -p "$chroot_dir/work/igi"
git -C "$repo" archive HEAD | tar -x -C "$chroot_dir/work/igi"
if ((with_shared)) && [ -d "$repo/../shared/scenes" ]; then
  mkdir -p "$chroot_dir/work/shared"
  cp -a "$repo/../shared/scenes" "$chroot_dir/work/shared/"
  echo "   with ../shared/scenes"
fi

# Runs one README command in the chroot, as a new user would type it at the tree's root.
overall=0
run_step() {
  local cmd="$1" log="$work/$(basename "$1" .sh).log" start status
  echo "== $cmd"
  start=$SECONDS
  set +e
  chroot "$chroot_dir" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    /bin/bash -c "cd /work/igi && $cmd" >"$log" 2>&1
  status=$?
  set -e
  echo "   exit $status after $(elapsed $((SECONDS - start)))"
  if ((status != 0)); then
    overall=1
    local first
    first="$(grep -m 1 -E '(^|[^a-z])([Ee]rror|ERROR|FAILED|[Ff]atal)' "$log" || true)"
    echo "   first error: ${first:-(none matched; last line: $(tail -n 1 "$log"))}"
    echo "   last lines of its output:"
    tail -n 15 "$log" | sed 's/^/   | /'
    # The root goes on the way out: its whole output stays, for a failure that does not show
    # again (a test that failed once in a fresh root passed in the next one).
    local kept="$work_parent/igi-fresh-$(date +%Y%m%d-%H%M%S)-$(basename "$cmd" .sh).log"
    cp "$log" "$kept" && echo "   its whole output: $kept"
  else
    echo "   last line: $(grep -v '^[[:space:]]*$' "$log" | tail -n 1)"
    # A passing ctest can still have skipped tests (no root, a missing tool): show its summary
    # lines and every skipped test, so that a pass says what ran.
    grep -E 'tests passed|\(Skipped\)$' "$log" | sed 's/^/   | /' || true
  fi
  return 0
}

run_step scripts/run.sh
run_step scripts/test.sh
if ((overall)); then
  echo "== FAILED on a fresh Debian 12 root"
else
  echo "== both README commands pass on a fresh Debian 12 root"
fi
exit "$overall"
