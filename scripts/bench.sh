#!/usr/bin/env bash
# Whole-program fast-pace benchmarks with `nctwin simulate` (release build), one table:
# blocks/s, IPO cycles/s, real-time factor (all by wall time), blocks per CPU second (the
# steadier figure on a shared machine), peak RSS and RSS beyond the program text per program.
#
#   scripts/bench.sh                 mill3 200k and 2M blocks (+ mill5, see below)
#   scripts/bench.sh --quick         mill3 20k only (a minute on a busy machine)
#   REPEAT=3 scripts/bench.sh        median of 3 runs per program (by wall time)
#
# mill5: the 5-axis program runs on the TRAORI presets: mill5-head-ca for 200k and 2M blocks,
# mill5-table-ac and mill5-mixed-bc for 200k (MILL5_MACHINE overrides the head preset). Should
# the preset be missing, the table says so in a "pending" row instead of a figure.
#
# Programs come from ../shared/bench/gen_program.py (GEN_PROGRAM=path to override) and are
# cached in target/bench/programs. The stage benchmarks (parse, prepare, interpolation per IPO
# cycle) are `cargo bench -p nctwin-engine`. Nothing here asserts a speed.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
GEN="${GEN_PROGRAM:-$ROOT/../shared/bench/gen_program.py}"
OUT="$ROOT/target/bench"
PROGRAMS="$OUT/programs"
REPEAT="${REPEAT:-1}"
MILL3_MACHINE="${MILL3_MACHINE:-mill-3axis}"
# The 5-axis program needs a machine with a TRAORI transformation.
MILL5_MACHINE="${MILL5_MACHINE:-mill5-head-ca}"

CASES=("mill3 200000 $MILL3_MACHINE" "mill3 2000000 $MILL3_MACHINE")
MILL5_CASES=("mill5 200000 $MILL5_MACHINE" "mill5 2000000 $MILL5_MACHINE" "mill5 200000 mill5-table-ac"
  "mill5 200000 mill5-mixed-bc")
if [ "${1:-}" = --quick ]; then
  CASES=("mill3 20000 $MILL3_MACHINE")
  MILL5_CASES=()
elif [ -n "${1:-}" ]; then
  echo "usage: $0 [--quick]" >&2
  exit 2
fi

if [ ! -f "$GEN" ]; then
  echo "error: no program generator at $GEN (set GEN_PROGRAM)" >&2
  exit 1
fi

if [ -z "${NCTWIN_BIN:-}" ]; then
  cargo build --release -q -p nctwin-server
  NCTWIN_BIN="${CARGO_TARGET_DIR:-$ROOT/target}/release/nctwin"
fi
mkdir -p "$PROGRAMS"

# mill5 hook: run the mill5 cases only on a machine that has the preset.
mill5_pending=""
if [ ${#MILL5_CASES[@]} -gt 0 ]; then
  probe="$OUT/probe.mpf"
  printf 'M30\n' >"$probe"
  if "$NCTWIN_BIN" simulate --machine "$MILL5_MACHINE" --compact "$probe" >/dev/null 2>"$OUT/stderr.txt"; then
    CASES+=("${MILL5_CASES[@]}")
  else
    mill5_pending="no preset $MILL5_MACHINE: $(head -c 120 "$OUT/stderr.txt")"
  fi
fi

# program KIND BLOCKS DIALECT -> path of the cached program
program() {
  local kind=$1 blocks=$2 dialect=$3 ext=mpf
  [ "$dialect" = rs274 ] && ext=ngc
  local path="$PROGRAMS/${kind}_${blocks}.${ext}"
  if [ ! -s "$path" ]; then
    python3 "$GEN" --kind "$kind" --blocks "$blocks" --dialect "$dialect" >"$path.tmp"
    mv "$path.tmp" "$path"
  fi
  echo "$path"
}

echo "machine: $(uname -srm), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)   binary: $NCTWIN_BIN   runs per program: $REPEAT"
echo

RESULTS="$OUT/bench-$(date +%Y%m%d-%H%M%S).jsonl"
: >"$RESULTS"
for case in "${CASES[@]}"; do
  read -r kind blocks machine <<<"$case"
  path="$(program "$kind" "$blocks" sinumerik)"
  for _ in $(seq "$REPEAT"); do
    code=0
    json="$("$NCTWIN_BIN" simulate --machine "$machine" --compact "$path" 2>"$OUT/stderr.txt")" || code=$?
    if [ -z "$json" ]; then
      # Usage errors (an unknown preset, say) print no JSON: note the reason in the table.
      json="$(python3 -c 'import json,sys; print(json.dumps({"skipped": sys.argv[1]}))' "$(head -c 200 "$OUT/stderr.txt")")"
    fi
    python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d.update(case=sys.argv[2], exit=int(sys.argv[3])); print(json.dumps(d))' \
      "$json" "$kind ${blocks} $machine" "$code" >>"$RESULTS"
  done
done

python3 - "$RESULTS" "$mill5_pending" <<'EOF'
import json, sys
from collections import defaultdict

runs = defaultdict(list)
for line in open(sys.argv[1]):
    d = json.loads(line)
    runs[d["case"]].append(d)

cols = ["program", "blocks", "IPO cycles", "sim time s", "wall s", "CPU s", "blocks/s", "blocks/CPU s", "cycles/s",
        "RT factor", "peak RSS MB", "RSS-text MB", "outcome"]
rows = []
dash = ["-"] * (len(cols) - 2)
for case, ds in runs.items():
    ok = [d for d in ds if "wall_time_s" in d]
    if not ok:
        rows.append([case, *dash, "skipped: " + ds[0].get("skipped", "?")])
        continue
    ok.sort(key=lambda d: d["wall_time_s"])
    d = ok[len(ok) // 2]
    outcome = d["outcome"]
    if outcome != "ended":
        alarms = d["state"]["alarms"] or [{"number": "", "message": ""}]
        errors = d.get("syntax_errors") or []
        why = errors[0]["message"] if errors else f'{alarms[0]["number"]} {alarms[0]["message"]}'
        outcome = f"{outcome}: {why}"[:70]
    rss = d["peak_rss_kib"] / 1024 if d.get("peak_rss_kib") else float("nan")
    cpu = d.get("cpu_time_s")
    rows.append([
        case, f'{d["blocks"]:,}', f'{d["ipo_cycles"]:,}', f'{d["simulated_time_s"]:.0f}', f'{d["wall_time_s"]:.2f}',
        f"{cpu:.2f}" if cpu is not None else "-",
        f'{d["blocks_per_s"]:,.0f}', f'{d["blocks"] / cpu:,.0f}' if cpu else "-", f'{d["cycles_per_s"]:,.0f}',
        f'{d["real_time_factor"]:,.0f}x', f"{rss:.1f}", f'{rss - d["program_bytes"] / 2**20:.1f}', outcome,
    ])
if sys.argv[2]:
    rows.append(["mill5", *dash, "pending: " + sys.argv[2]])
widths = [max(len(str(r[i])) for r in rows + [cols]) for i in range(len(cols))]
fmt = lambda r: "  ".join(str(v).rjust(w) if 0 < i < len(cols) - 1 else str(v).ljust(w) for i, (v, w) in enumerate(zip(r, widths)))
print(fmt(cols))
print(fmt(["-" * w for w in widths]))
for r in rows:
    print(fmt(r))
EOF
echo
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)   raw results: $RESULTS"
