#!/usr/bin/env bash
# Frame rate against link rate (docs/PERFORMANCE.md, "Across network links"): sets up and builds
# (scripts/setup.sh, plus iproute2), then runs sessions whose master and clients are "hosts" made
# of network namespaces on this machine (as tests/NetworkLab.h makes them: veth pairs to a bridge,
# addresses 10.213.0.0/24 that exist only inside them), with tc's token bucket filter (tbf)
# limiting either each client's link or the master's uplink that all clients share.
#   1. Two rendering clients (one thread each): fps and wire bytes per pixel for each rate, at
#      640x480 and 1280x960.
#   2. The link a master needs: 1, 2 and 4 replaying clients (igi-client --replay resends each
#      tile's first result, so they cost next to no CPU and stand for clients as fast as one
#      likes) behind the master's uplink at each rate: the frame rate that link carries, measured.
# Writes docs/perf/network.json, docs/perf/network.png and the generated block of
# docs/PERFORMANCE.md. Needs root. About 8 minutes on 2 cores. This kernel has no netem, so
# links differ in rate only: latency is not emulated.
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# Usage: scripts/bench_network.sh [--rates "10 100 1000"] [--frames 16]
#                                 [--replay-rates "100 1000"] [--replay-frames 48]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rates="10 100 1000"
frames=16
replay_rates="100 1000"
replay_frames=48
replay_clients="1 2 4"
while (($#)); do
  case "$1" in
    --rates) rates="$2"; shift ;;
    --frames) frames="$2"; shift ;;
    --replay-rates) replay_rates="$2"; shift ;;
    --replay-frames) replay_frames="$2"; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench_network: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ "$(id -u)" -ne 0 ]; then
  echo "bench_network: needs root (network namespaces and tc)" >&2
  exit 2
fi
# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build iproute2
cd "$root"
out="$root/out/bench-network"
mkdir -p "$out" docs/perf
prefix="igibench$$-"
clients=2  # rendering clients of part 1
hosts=4    # client hosts: the most replaying clients of part 2

lab_down() {
  local i
  for i in $(seq 0 "$hosts"); do ip netns del "${prefix}h$i" 2>/dev/null || true; done
  ip netns del "${prefix}sw" 2>/dev/null || true
}
trap lab_down EXIT

lab_up() {
  local i
  ip netns add "${prefix}sw"
  ip -n "${prefix}sw" link add br0 type bridge
  ip -n "${prefix}sw" link set br0 up
  for i in $(seq 0 "$hosts"); do
    ip netns add "${prefix}h$i"
    ip link add eth0 netns "${prefix}h$i" type veth peer name "p$i" netns "${prefix}sw"
    ip -n "${prefix}h$i" addr add "10.213.0.$((i + 1))/24" dev eth0
    ip -n "${prefix}h$i" link set lo up
    ip -n "${prefix}h$i" link set eth0 up
    ip -n "${prefix}sw" link set "p$i" master br0
    ip -n "${prefix}sw" link set "p$i" up
  done
}

tbf() {  # tbf NAMESPACE DEVICE MBIT (0: no limit)
  tc -n "$1" qdisc del dev "$2" root 2>/dev/null || true
  if [ "$3" -gt 0 ]; then
    tc -n "$1" qdisc add dev "$2" root tbf rate "${3}mbit" burst 64kb latency 100ms
  fi
}

secret="$out/cluster.secret"
head -c 32 /dev/urandom | base64 >"$secret"
chmod 600 "$secret"

# Bytes the switch has sent toward the master: the uplink's own count, headers and all.
uplink_bytes() {
  ip -n "${prefix}sw" -s -j link show dev p0 |
    /usr/bin/python3 -c 'import json, sys; print(json.load(sys.stdin)[0]["stats64"]["tx"]["bytes"])'
}

# run NAME WIDTH HEIGHT [CLIENTS FRAMES [CLIENT FLAGS...]]: one session, master on host 0,
# clients on hosts 1..CLIENTS.
run() {
  local name="$1" w="$2" h="$3" n="${4:-$clients}" f="${5:-$frames}" i pids=()
  shift $(($# < 5 ? $# : 5))
  local sent
  sent=$(uplink_bytes)
  ip netns exec "${prefix}h0" "$build/bin/igi-master" --scene scenes/cornell/cornell.json \
    --width "$w" --height "$h" --frames "$f" --clients "$n" \
    --listen 10.213.0.1:7878 --secret-file "$secret" --stats-json "$out/$name.json" \
    >"$out/$name.log" 2>&1 &
  local master=$!
  sleep 0.3
  for i in $(seq 1 "$n"); do
    ip netns exec "${prefix}h$i" "$build/bin/igi-client" --connect 10.213.0.1:7878 --threads 1 \
      --secret-file "$secret" "$@" >"$out/$name.client$i.log" 2>&1 &
    pids+=($!)
  done
  wait "$master"
  for i in "${pids[@]}"; do wait "$i" || true; done
  echo $(($(uplink_bytes) - sent)) >"$out/$name.uplink-bytes"
  echo "   $name: $(grep -o '[0-9.]* fps$' "$out/$name.log" | tail -n 1)"
}

lab_up
start=$SECONDS
# 1. Two rendering clients: each client's link limited, then the master's uplink.
for size in 640x480 1280x960; do
  w=${size%x*} h=${size#*x}
  echo "== $size"
  for i in $(seq 1 "$clients"); do tbf "${prefix}h$i" eth0 0; done
  tbf "${prefix}sw" p0 0
  run "$size-unlimited" "$w" "$h"
  for r in $rates; do
    for i in $(seq 1 "$clients"); do tbf "${prefix}h$i" eth0 "$r"; done
    run "$size-client-$r" "$w" "$h"
    for i in $(seq 1 "$clients"); do tbf "${prefix}h$i" eth0 0; done
    # The master's uplink: what the switch sends toward the master, shared by every client.
    tbf "${prefix}sw" p0 "$r"
    run "$size-uplink-$r" "$w" "$h"
    tbf "${prefix}sw" p0 0
  done
done
# 2. The link a master needs for N clients: replaying clients, the master's uplink limited.
for size in 640x480 1280x960; do
  w=${size%x*} h=${size#*x}
  echo "== $size, replaying clients behind the master's uplink"
  for n in $replay_clients; do
    for r in $replay_rates 0; do
      tbf "${prefix}sw" p0 "$r"
      run "$size-replay$n-uplink-$r" "$w" "$h" "$n" "$replay_frames" --replay
    done
    tbf "${prefix}sw" p0 0
  done
done
seconds=$((SECONDS - start))
/usr/bin/python3 "$root/scripts/network_report.py" "$out" "$rates" "$replay_rates" \
  "$replay_clients" "$clients" "$frames" "$replay_frames" "$seconds"
