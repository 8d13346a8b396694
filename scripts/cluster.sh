#!/usr/bin/env bash
# Runs one session on the machines of a hosts file, over the ssh you already use:
#  1. checks every host: reachable by ssh (non-interactive), and its igi-client is this build;
#  2. installs the cluster secret on each, mode 600, through ssh's standard input (never on a
#     command line that ps would show);
#  3. starts the master here with the arguments after `--`, then a client on every host;
#  4. prints one status line per host every few seconds (from the master's control port);
#  5. collects every log into one folder;
#  6. stops everything it started (clients, master, the secret's copies) when the master ends,
#     fails, or this script is interrupted (Ctrl-C, SIGTERM).
# Why a shell script: every step is an ssh or a process to start and stop, which is what a shell
# does; it needs nothing on the hosts but sshd and the client, and nothing here but OpenSSH's
# client (no agent of our own, no Python).
#
# Usage: scripts/cluster.sh --hosts FILE [options] -- MASTER_ARGUMENTS...
# The hosts file has one host per line: HOST THREADS [USER] [PORT] ('#' starts a comment; '-'
# for the ssh default user when a port follows; THREADS 0: every core of that host).
# Options:
#   --hosts FILE           the hosts file (required)
#   --master-address ADDR  the address the clients reach this machine at (default: the one this
#                          machine's route to the first host uses)
#   --port N               the port the master listens on for clients (default 7878)
#   --secret-file FILE     the cluster secret (default: a random one made for this session, in
#                          the log folder)
#   --ssh-config FILE      given to ssh as -F (identities, known hosts, jump hosts)
#   --bin DIR              the folder holding igi-client on the hosts (default: this build's
#                          bin folder, the same path on every host)
#   --remote-dir DIR       where each host keeps the session's secret (default .igi-cluster, in
#                          the ssh user's home); the session's subfolder is removed at the end
#   --logs DIR             the log folder (default cluster-logs/<date>-<time>)
#   --status-seconds S     seconds between status lines (default 5; 0: none)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

die() {
  echo "cluster.sh: $*" >&2
  exit 2
}
# A command that fails unchecked ends the script (set -e); this names it rather than leaving
# only the exit code.
trap 'echo "cluster.sh: line $LINENO: \`$BASH_COMMAND\` failed (exit $?)" >&2' ERR
say() { echo "[cluster] $*" | tee -a "$logs/cluster.log"; }

hosts_file="" master_address="" port=7878 secret="" ssh_config=""
local_bin="$root/build/bin" remote_bin="" remote_dir=".igi-cluster" logs="" status_seconds=5
while (($#)); do
  case "$1" in
    --hosts) hosts_file="${2:?--hosts needs a file}"; shift 2 ;;
    --master-address) master_address="${2:?--master-address needs an address}"; shift 2 ;;
    --port) port="${2:?--port needs a number}"; shift 2 ;;
    --secret-file) secret="${2:?--secret-file needs a file}"; shift 2 ;;
    --ssh-config) ssh_config="${2:?--ssh-config needs a file}"; shift 2 ;;
    --bin) remote_bin="${2:?--bin needs a folder}"; shift 2 ;;
    --remote-dir) remote_dir="${2:?--remote-dir needs a folder}"; shift 2 ;;
    --logs) logs="${2:?--logs needs a folder}"; shift 2 ;;
    --status-seconds) status_seconds="${2:?--status-seconds needs a number}"; shift 2 ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    *) die "unknown option '$1' (the master's arguments go after --; see --help)" ;;
  esac
done
master_args=("$@")
[ -n "$hosts_file" ] || die "--hosts FILE is required (see --help)"
[ -r "$hosts_file" ] || die "cannot read the hosts file '$hosts_file'"
[[ "$port" =~ ^[0-9]+$ ]] || die "--port '$port' is not a number"
[[ "$status_seconds" =~ ^[0-9]+$ ]] || die "--status-seconds '$status_seconds' is not a whole number"
control_arg=(--control 127.0.0.1:0)  # the master's own --control, if given, is used instead
for a in "${master_args[@]}"; do
  case "$a" in
    --control | --control=*) control_arg=() ;;
    --listen | --listen=* | --clients | --clients=* | --secret-file | --secret-file=* | \
      --local-clients | --local-clients=* | --insecure)
      die "the master's $a is the launcher's to set (see --help)" ;;
  esac
done
remote_bin="${remote_bin:-$local_bin}"
[ -x "$local_bin/igi-master" ] || die "no $local_bin/igi-master: build first (scripts/setup.sh)"

# ---- the hosts file
names=() threads=() users=() ports=()
line_no=0
while IFS= read -r line || [ -n "$line" ]; do
  line_no=$((line_no + 1))
  line="${line%%#*}"
  read -r -a f <<<"$line" || true
  ((${#f[@]})) || continue
  where="$hosts_file line $line_no"
  ((${#f[@]} >= 2 && ${#f[@]} <= 4)) || die "$where: want HOST THREADS [USER] [PORT], got '${line}'"
  [[ "${f[1]}" =~ ^[0-9]+$ ]] || die "$where: THREADS '${f[1]}' is not a whole number"
  [[ -z "${f[3]:-}" || "${f[3]}" =~ ^[0-9]+$ ]] || die "$where: PORT '${f[3]}' is not a number"
  names+=("${f[0]}") threads+=("${f[1]}") users+=("${f[2]:--}") ports+=("${f[3]:-}")
done <"$hosts_file"
n=${#names[@]}
((n > 0)) || die "$hosts_file names no host"

started="$(date +%Y%m%d-%H%M%S)"
session="$started-$$"
logs="${logs:-cluster-logs/$started}"
mkdir -p "$logs"
: >"$logs/cluster.log"

# ssh to host i with the options every call shares; BatchMode: fail rather than ask for a
# password, since nobody is there to type it.
ssh_to() {
  local i=$1
  shift
  local o=(-o BatchMode=yes -o ConnectTimeout=10 -o ServerAliveInterval=10)
  [ "$1" = "-n" ] && { o+=(-n); shift; }
  [ -n "$ssh_config" ] && o+=(-F "$ssh_config")
  [ "${users[i]}" != "-" ] && o+=(-l "${users[i]}")
  [ -n "${ports[i]}" ] && o+=(-p "${ports[i]}")
  ssh "${o[@]}" "${names[i]}" "$@"
}
q() { printf '%q' "$1"; }  # one word for the remote shell
host_dir() { echo "$remote_dir/$session-$1"; }

# ---- 1. every host reachable and of this build (all at once: a dead host costs one timeout)
build="$("$local_bin/igi-master" --version)"
say "session $session, build $build, $n hosts, logs in $logs"
for ((i = 0; i < n; i++)); do
  ssh_to "$i" -n "$(q "$remote_bin/igi-client") --version" >"$logs/check-$i.out" 2>&1 &
  check_pids[i]=$!
done
failed=0
for ((i = 0; i < n; i++)); do
  rc=0
  wait "${check_pids[i]}" || rc=$?
  out="$(tail -n 1 "$logs/check-$i.out")"
  if ((rc == 255)); then
    say "${names[i]}: not reachable over ssh: $out"
    failed=1
  elif ((rc != 0)); then
    say "${names[i]}: '$remote_bin/igi-client --version' failed (exit $rc): $out"
    failed=1
  elif [ "$out" != "$build" ]; then
    say "${names[i]}: its igi-client is build '$out', this master is build '$build'"
    failed=1
  fi
done
((failed == 0)) || die "not starting: a host failed its check (above; logs in $logs)"

# Each host's IPv4 address, once: the status lines match clients to hosts by it.
addresses=()
for ((i = 0; i < n; i++)); do
  addresses[i]="$(getent ahostsv4 "${names[i]}" | awk 'NR == 1 { print $1 }')"
done

# ---- where the master listens: the address this machine's route to the first host leaves from
if [ -z "$master_address" ]; then
  first="${addresses[0]}"
  [ -n "$first" ] && master_address="$(ip -4 -o route get "$first" 2>/dev/null |
    sed -n 's/.* src \([0-9.]*\).*/\1/p')"
  [ -n "$master_address" ] || die "cannot tell this machine's address toward ${names[0]}: give --master-address"
fi

# ---- 2. the secret: given, or made for this session; copied through ssh's standard input
if [ -z "$secret" ]; then
  secret="$logs/cluster.secret"
  (umask 077 && head -c 32 /dev/urandom | base64 >"$secret")
fi
[ -r "$secret" ] || die "cannot read the secret file '$secret'"

# From here on, everything started is stopped on the way out, however it goes.
master_pid="" client_pids=() installed=() stopping=0
stop_all() {
  local rc=$?
  ((stopping)) && return
  stopping=1
  trap '' INT TERM
  if [ -n "$master_pid" ] && kill -0 "$master_pid" 2>/dev/null; then
    say "stopping the master"
    kill -TERM "$master_pid" 2>/dev/null || true
    for _ in $(seq 100); do kill -0 "$master_pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$master_pid" 2>/dev/null || true
  fi
  for ((i = 0; i < n; i++)); do
    local remote_pid=""
    [ -f "$logs/client-$i.log" ] &&
      remote_pid="$(sed -n 's/^igi-cluster: client pid \([0-9]*\)$/\1/p' "$logs/client-$i.log" | head -n 1)"
    local cmd=""
    # The client ends by itself when the master says so; one that did not is ended here. Only
    # if that pid is still an igi-client: once it ended, the pid may be another process's.
    [ -n "$remote_pid" ] &&
      cmd="if [ \"\$(cat /proc/$remote_pid/comm 2>/dev/null)\" = igi-client ]; then kill $remote_pid; fi; "
    [ -n "${installed[i]:-}" ] && cmd+="rm -rf $(q "$(host_dir "$i")")"
    [ -n "$cmd" ] && { ssh_to "$i" -n "$cmd" >>"$logs/cleanup-$i.log" 2>&1 || say "${names[i]}: clean-up failed (see $logs/cleanup-$i.log)"; }
    [ -n "${client_pids[i]:-}" ] && kill "${client_pids[i]}" 2>/dev/null || true
  done
  wait 2>/dev/null || true
  say "stopped everything it started (exit $rc)"
  exit "$rc"
}
trap stop_all EXIT
trap 'say "interrupted"; exit 130' INT
trap 'say "terminated"; exit 143' TERM

for ((i = 0; i < n; i++)); do
  dir="$(host_dir "$i")"
  installed[i]=1
  ssh_to "$i" "umask 077 && mkdir -p $(q "$dir") && cat > $(q "$dir/secret")" <"$secret" \
    >"$logs/secret-$i.log" 2>&1 || die "${names[i]}: could not install the secret (see $logs/secret-$i.log)"
done

# ---- 3. the master, then the clients
# The log exists before tee (started in its own process) opens it: the loop below reads it at
# once, and a sed that cannot open its file exits 2, which set -e and pipefail would make this
# script's silent exit.
: >"$logs/master.log"
"$local_bin/igi-master" --listen "$master_address:$port" --clients "$n" --secret-file "$secret" \
  "${control_arg[@]}" "${master_args[@]}" > >(tee "$logs/master.log") 2>&1 &
master_pid=$!
control=""
for _ in $(seq 300); do
  control="$(sed -n 's/.*control commands on \([0-9.]*:[0-9]*\).*/\1/p' "$logs/master.log" | head -n 1)"
  [ -n "$control" ] && break
  kill -0 "$master_pid" 2>/dev/null || break
  sleep 0.1
done
[ -n "$control" ] || { wait "$master_pid" || true; master_pid=""; die "the master did not start (see $logs/master.log)"; }

for ((i = 0; i < n; i++)); do
  dir="$(host_dir "$i")"
  # The client's pid comes first in its log, so that the clean-up can end it even if this ssh
  # is gone; exec keeps it that pid.
  ssh_to "$i" -n "echo igi-cluster: client pid \$\$; exec $(q "$remote_bin/igi-client") \
--connect $(q "$master_address:$port") --threads ${threads[i]} --secret-file $(q "$dir/secret")" \
    >"$logs/client-$i.log" 2>&1 &
  client_pids[i]=$!
done
say "master on $master_address:$port (control $control), clients started on: ${names[*]}"

# ---- 4. status lines until the master ends
status() {
  local table
  table="$("$local_bin/igi-ctl" --connect "$control" status --table 2>/dev/null)" || return 0
  local kind a b c d e done_ total fps
  declare -A seen=()
  while read -r kind a b c d e; do
    case "$kind" in
      session) done_=$a total=$b fps=$c ;;
      client) seen["${a%:*}"]="$b threads, $c tiles/s, $d Mrays/s ($e)" ;;
    esac
  done <<<"$table"
  say "frames ${done_:-?}/${total:-?}, ${fps:-?} fps"
  for ((i = 0; i < n; i++)); do
    local address="${addresses[i]}"
    if [ -n "$address" ] && [ -n "${seen[$address]:-}" ]; then
      say "  ${names[i]}: ${seen[$address]}"
    elif kill -0 "${client_pids[i]}" 2>/dev/null; then
      say "  ${names[i]}: not connected (its ssh runs; see $logs/client-$i.log)"
    else
      say "  ${names[i]}: gone (see $logs/client-$i.log)"
    fi
  done
}
ticks=$((status_seconds > 0 ? status_seconds * 10 : 10))  # of 0.1 s
# A first line at once (the master answers, the clients are on their way): a short session can
# end before the first interval does, and would show none.
((status_seconds > 0)) && status
while kill -0 "$master_pid" 2>/dev/null; do
  for ((t = 0; t < ticks; t++)); do
    kill -0 "$master_pid" 2>/dev/null || break 2
    sleep 0.1
  done
  ((status_seconds > 0)) && status
done
rc=0
wait "$master_pid" || rc=$?
master_pid=""
say "the master ended with exit code $rc"
exit "$rc"
