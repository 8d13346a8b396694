#!/usr/bin/env bash
# Frame rate against link rate (docs/PERFORMANCE.md, "Across network links"): sets up and builds
# (scripts/setup.sh, plus iproute2), then runs sessions whose master and clients are "hosts" made
# of network namespaces on this machine (as tests/NetworkLab.h makes them: veth pairs to a bridge,
# addresses 10.213.0.0/24 that exist only inside them), with tc's token bucket filter (tbf)
# limiting either each client's link or the master's uplink that all clients share. Reports fps
# and wire bytes per pixel for each rate at 640x480 and 1280x960 with two clients (one thread
# each), into docs/perf/network.json and the generated block of docs/PERFORMANCE.md.
# Needs root. About 6 minutes on 2 cores. This kernel has no netem, so links differ in rate only:
# latency is not emulated.
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# Usage: scripts/bench_network.sh [--rates "10 100 1000"] [--frames 16]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rates="10 100 1000"
frames=16
while (($#)); do
  case "$1" in
    --rates) rates="$2"; shift ;;
    --frames) frames="$2"; shift ;;
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
clients=2

lab_down() {
  local i
  for i in $(seq 0 "$clients"); do ip netns del "${prefix}h$i" 2>/dev/null || true; done
  ip netns del "${prefix}sw" 2>/dev/null || true
}
trap lab_down EXIT

lab_up() {
  local i
  ip netns add "${prefix}sw"
  ip -n "${prefix}sw" link add br0 type bridge
  ip -n "${prefix}sw" link set br0 up
  for i in $(seq 0 "$clients"); do
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

# run NAME WIDTH HEIGHT: one session, master on host 0, clients on hosts 1..$clients.
run() {
  local name="$1" w="$2" h="$3" i pids=()
  ip netns exec "${prefix}h0" "$build/bin/igi-master" --scene scenes/cornell/cornell.json \
    --width "$w" --height "$h" --frames "$frames" --clients "$clients" \
    --listen 10.213.0.1:7878 --secret-file "$secret" --stats-json "$out/$name.json" \
    >"$out/$name.log" 2>&1 &
  local master=$!
  sleep 0.3
  for i in $(seq 1 "$clients"); do
    ip netns exec "${prefix}h$i" "$build/bin/igi-client" --connect 10.213.0.1:7878 --threads 1 \
      --secret-file "$secret" >"$out/$name.client$i.log" 2>&1 &
    pids+=($!)
  done
  wait "$master"
  for i in "${pids[@]}"; do wait "$i" || true; done
  echo "   $name: $(grep -o '[0-9.]* fps$' "$out/$name.log" | tail -n 1)"
}

lab_up
start=$SECONDS
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
seconds=$((SECONDS - start))
/usr/bin/python3 - "$out" "$rates" "$clients" "$frames" "$seconds" <<'PY'
import json, os, re, statistics, subprocess, sys, datetime
out, rates, clients, frames, seconds = sys.argv[1], sys.argv[2].split(), int(sys.argv[3]), sys.argv[4], int(sys.argv[5])
def load(name):
    with open(os.path.join(out, name + ".json")) as f:
        s = json.load(f)
    bpp = statistics.mean(fr["wire_bytes_per_pixel"] for fr in s["frames"])
    return {"fps": s["fps"], "bytes_per_pixel": bpp}
results = {}
for size in ("640x480", "1280x960"):
    r = {"unlimited": load(f"{size}-unlimited")}
    for rate in rates:
        r[f"client-{rate}"] = load(f"{size}-client-{rate}")
        r[f"uplink-{rate}"] = load(f"{size}-uplink-{rate}")
    results[size] = r
with open("docs/perf/network.json", "w") as f:
    json.dump(results, f, indent=1)
rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
L = [f"Measured on {datetime.date.today()} by `scripts/bench_network.sh` ({seconds // 60} min {seconds % 60} s), "
     f"build `{rev}`, on this 2-core machine: the default scene, paper settings, {frames} frames a run, "
     f"a master and {clients} clients (one thread each) on hosts made of network namespaces joined by a "
     "bridge, each link limited by tc's token bucket filter. 'Each client' limits every client's own "
     "link; 'master uplink' limits what reaches the master, shared by all clients. No latency is "
     "emulated (this kernel has no netem).", "",
     "| image | link limit | each client: fps | master uplink: fps | wire bytes / pixel |",
     "|---|---|---|---|---|"]
for size, r in results.items():
    u = r["unlimited"]
    L.append(f"| {size} | none | {u['fps']:.2f} | {u['fps']:.2f} | {u['bytes_per_pixel']:.2f} |")
    for rate in rates:
        c, m = r[f"client-{rate}"], r[f"uplink-{rate}"]
        L.append(f"| {size} | {rate} Mbit/s | {c['fps']:.2f} | {m['fps']:.2f} | {c['bytes_per_pixel']:.2f} |")
L.append("")
for size, r in results.items():
    u = r["unlimited"]["fps"]
    enough = [rate for rate in rates if r[f"uplink-{rate}"]["fps"] >= 0.95 * u]
    need = (f"{enough[0]} Mbit/s was enough" if enough else "none of the rates tried was enough")
    w, h = map(int, size.split("x"))
    mbit = r["unlimited"]["bytes_per_pixel"] * w * h * u * 8e-6
    L.append(f"- {size}: at {u:.2f} fps the clients sent {mbit:.1f} Mbit/s in all; for the master's "
             f"uplink {need} to keep 95 % of the unlimited frame rate.")
block = "\n".join(L)
doc = "docs/PERFORMANCE.md"
text = open(doc, encoding="utf-8").read()
pat = re.compile(r"(<!-- BEGIN GENERATED network -->\n).*?(\n?<!-- END GENERATED network -->)", re.S)
if not pat.search(text):
    sys.exit(f"{doc} has no <!-- BEGIN GENERATED network --> block")
text = pat.sub(lambda m: m.group(1) + block + "\n" + m.group(2).lstrip("\n"), text)
open(doc, "w", encoding="utf-8").write(text)
print(block)
PY
