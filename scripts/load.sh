#!/usr/bin/env bash
# Load test: for each N, a fresh server (release build) with N real-time sessions, each running
# a long program with one WebSocket viewer (20 Hz), measured by tools/loadgen over a window:
# IPO lag (did any session fall behind wall time), server CPU, state frames per session and
# second, and command-to-frame latency percentiles (NC stop/start on 50 probe sessions).
#
#   scripts/load.sh                  N = 100 500 1000 2000, 30 s window each
#   scripts/load.sh 100 200          other N
#   DURATION=60 scripts/load.sh      longer window
#
# The client runs on the same machine as the server, at lower priority (LOADGEN_NICE, default
# 10) so that it takes what the server leaves; its CPU is reported beside the server's. Other
# processes compete too: the load average and the time the server's threads waited for a CPU
# (run queue) are printed with every row, and the server's CPU per session and second is the
# figure that does not depend on them.
#
# Lag: "drift" is how far a session's simulated time fell behind wall time, judged per second
# by its most promptly delivered frame (delivery delays do not count); "wake p99" is the
# server's own IPO lag (lateness of the real-time wake-ups, from /metrics); "frame lag" is the
# old client-side figure that includes every delivery delay. Behind: drift above 250 ms.
# Nothing here asserts a figure.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
DURATION="${DURATION:-30}"
WARMUP="${WARMUP:-3}"
GEN="${GEN_PROGRAM:-$ROOT/../shared/bench/gen_program.py}"
OUT="$ROOT/target/bench"
NS=("$@")
[ ${#NS[@]} -gt 0 ] || NS=(100 500 1000 2000)
mkdir -p "$OUT/programs"

# Thousands of sockets on both ends.
ulimit -n 65536 2>/dev/null || ulimit -n "$(ulimit -Hn)"

if [ -z "${NCTWIN_BIN:-}" ] || [ -z "${LOADGEN_BIN:-}" ]; then
  cargo build --release -q -p nctwin-server -p nctwin-loadgen
fi
TARGET="${CARGO_TARGET_DIR:-$ROOT/target}/release"
NCTWIN_BIN="${NCTWIN_BIN:-$TARGET/nctwin}"
LOADGEN_BIN="${LOADGEN_BIN:-$TARGET/nctwin-loadgen}"

# A program that outlasts warm-up and window in real time: mill3, 2,000 blocks (about 560 s).
PROGRAM="$OUT/programs/load_mill3_2000.mpf"
[ -s "$PROGRAM" ] || python3 "$GEN" --kind mill3 --blocks 2000 >"$PROGRAM"

# Session limits of the server, raised when it has the flags.
HELP="$("$NCTWIN_BIN" --help)"
limit_flags=()
if grep -q -- '--max-sessions ' <<<"$HELP"; then limit_flags+=(--max-sessions 100000); fi
if grep -q -- '--max-sessions-per-ip' <<<"$HELP"; then limit_flags+=(--max-sessions-per-ip 100000); fi
if grep -q -- '--max-connections-per-ip' <<<"$HELP"; then limit_flags+=(--max-connections-per-ip 100000); fi

SERVER_PID=""
DATA_DIR=""
cleanup() {
  if [ -n "$SERVER_PID" ]; then
    kill "$SERVER_PID" 2>/dev/null || true
    wait "$SERVER_PID" 2>/dev/null || true
  fi
  [ -n "$DATA_DIR" ] && rm -rf "$DATA_DIR"
  SERVER_PID="" DATA_DIR=""
}
trap cleanup EXIT

RESULTS="$OUT/load-$(date +%Y%m%d-%H%M%S).jsonl"
: >"$RESULTS"
echo "machine: $(uname -srm), $(nproc) cores; window ${DURATION} s after ${WARMUP} s warm-up; server $NCTWIN_BIN ${limit_flags[*]}"
for n in "${NS[@]}"; do
  DATA_DIR="$(mktemp -d "${TMPDIR:-/tmp}/nctwin-load.XXXXXX")"
  LOG="$DATA_DIR/server.log"
  RUST_LOG="${RUST_LOG:-warn,nctwin=info}" NO_COLOR=1 "$NCTWIN_BIN" --bind 127.0.0.1:0 --data-dir "$DATA_DIR/data" "${limit_flags[@]}" >"$LOG" 2>&1 &
  SERVER_PID=$!
  URL=""
  for _ in $(seq 300); do
    URL="$(grep -oE 'listening on http://[0-9.:]+' "$LOG" | head -n1 | sed 's/^listening on //')" || true
    [ -n "$URL" ] && break
    sleep 0.1
  done
  if [ -z "$URL" ]; then
    echo "N=$n: the server did not start: $(tail -n 5 "$LOG")" >&2
    exit 1
  fi
  echo "N=$n: server pid $SERVER_PID at $URL, load before $(cut -d' ' -f1-3 /proc/loadavg)" >&2
  if nice -n "${LOADGEN_NICE:-10}" "$LOADGEN_BIN" --url "$URL" --sessions "$n" --program "$PROGRAM" --duration "$DURATION" --warmup "$WARMUP" \
      --server-pid "$SERVER_PID" --json >>"$RESULTS" 2>"$OUT/loadgen-$n.log"; then
    :
  else
    echo "N=$n: loadgen failed: $(tail -n 3 "$OUT/loadgen-$n.log")" >&2
    printf '{"sessions": %s, "failed": %s}\n' "$n" "$(tail -n1 "$OUT/loadgen-$n.log" | python3 -c 'import json,sys; print(json.dumps(sys.stdin.read().strip()))')" >>"$RESULTS"
  fi
  echo "N=$n: load after $(cut -d' ' -f1-3 /proc/loadavg)" >&2
  cleanup
done

python3 - "$RESULTS" <<'EOF'
import json, sys
cols = ["N", "load", "server CPU % (sys)", "ms/sess/s", "runq wait %", "client CPU %", "RSS MB", "frames/sess/s p50 (min)",
        "drift max p50/p99/max ms", "behind", "wake p99 <= ms (>250ms)", "frame lag p99/max ms", "cmd->frame p50/p99 ms", "timeouts"]
rows = []
for line in open(sys.argv[1]):
    d = json.loads(line)
    if "failed" in d:
        rows.append([str(d["sessions"]), "failed: " + d["failed"][:80]] + [""] * (len(cols) - 2))
        continue
    f = lambda v, p=0: "-" if v is None else f"{v:.{p}f}"
    l, c, dr, w = d["lag_ms"], d["latency_ms"], d.get("drift_ms") or {}, d.get("server_wakes") or {}
    wake = "-" if not w else f'{f(None if w.get("p99_le_s") is None else w["p99_le_s"] * 1000)} ({w["later_than_behind"]}/{w["wakes"]})'
    rows.append([
        str(d["sessions"]), f(d.get("load_avg_1m"), 1),
        f'{f(d["server_cpu_percent"])} ({f(d.get("server_sys_cpu_percent"))})', f(d.get("server_cpu_ms_per_session_s"), 3),
        f(d.get("server_runqueue_wait_percent")), f(d["client_cpu_percent"]), f(d["server_rss_mib"]),
        f'{d["frames_per_session_per_s"]["p50"]:.1f} ({d["frames_per_session_per_s"]["min"]:.1f})',
        f'{f(dr.get("max_p50"))}/{f(dr.get("max_p99"))}/{f(dr.get("max_max"))}', f'{d["behind"]}/{l["sessions"]}', wake,
        f'{f(l["max_p99"])}/{f(l["max_max"])}', f'{f(c["p50"])}/{f(c["p99"])}', f'{c["timeouts"]}/{c["samples"] + c["timeouts"]}',
    ])
w = [max(len(r[i]) for r in rows + [cols]) for i in range(len(cols))]
print()
print("  ".join(c.rjust(w[i]) for i, c in enumerate(cols)))
for r in rows:
    print("  ".join(v.rjust(w[i]) for i, v in enumerate(r)))
print("\nCPU %: of one core (200 = both cores); ms/sess/s: server CPU ms per session and second of the window;")
print("runq wait %: time the server's threads waited for a CPU (other processes on the machine), % of one core.")
print("drift: per session the largest fall of simulated time behind wall time, per second by the most promptly")
print("delivered frame; behind: drift above 250 ms. wake p99: bucket bound of the server's wake-up lateness (IPO lag)")
print("and wake-ups later than 250 ms. frame lag: the client-side lag including delivery delays. raw:", sys.argv[1])
EOF
