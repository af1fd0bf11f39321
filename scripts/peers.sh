#!/usr/bin/env bash
# NCTwin side by side with the peers of ../shared/TOOLING.md, in one run, on the same
# generated toolpath (../shared/bench/gen_program.py mill3): the peers read the RS274 version,
# NCTwin the Sinumerik version. Whole process each, median of RUNS (hyperfine when installed).
#
#   scripts/peers.sh [BLOCKS]        default 200000; RUNS=3; NCTWIN_BIN=path skips the build
#
# Installs what is missing (takes minutes the first time; not part of CI):
#   - LinuxCNC's interpreter `rs274` (apt: linuxcnc-uspace), hyperfine (apt)
#   - cncjs's gcode-toolpath (npm, into target/bench/peers/node)
#   - nc-gcode-interpreter (PyPI, into the venv target/bench/peers/venv; it reads the
#     Sinumerik dialect, so it gets the Sinumerik file)
# Everything it installs or writes stays under target/ (git-ignored), except the apt packages.
#
# Rows: `nctwin interpret` is block preparation only (parse + interpret into moves, like the
# peers, which translate a program into motion segments and do no interpolation);
# `nctwin simulate` adds look-ahead and interpolation of every IPO cycle.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BLOCKS="${1:-200000}"
RUNS="${RUNS:-3}"
GEN="${GEN_PROGRAM:-$ROOT/../shared/bench/gen_program.py}"
PEERS="$ROOT/target/bench/peers"
PROGRAMS="$ROOT/target/bench/programs"
mkdir -p "$PEERS/node" "$PROGRAMS"

say() { printf '==> %s\n' "$*" >&2; }

# --- install -------------------------------------------------------------------------------
apt_missing=()
command -v rs274 >/dev/null || apt_missing+=(linuxcnc-uspace)
command -v hyperfine >/dev/null || apt_missing+=(hyperfine)
if [ ${#apt_missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    say "apt-get install ${apt_missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${apt_missing[@]}" >/dev/null
  else
    say "not root: cannot install ${apt_missing[*]}; those rows are skipped"
  fi
fi
if command -v npm >/dev/null && [ ! -d "$PEERS/node/node_modules/gcode-toolpath" ]; then
  say "npm install gcode-toolpath"
  mkdir -p "$PEERS/node"
  (cd "$PEERS/node" && { [ -f package.json ] || npm init -y >/dev/null; } &&
    npm install --no-audit --no-fund --silent gcode-toolpath >/dev/null)
fi
if [ ! -x "$PEERS/venv/bin/python" ]; then
  say "python venv + nc-gcode-interpreter"
  python3 -m venv "$PEERS/venv"
fi
if ! "$PEERS/venv/bin/python" -c 'import nc_gcode_interpreter' 2>/dev/null; then
  "$PEERS/venv/bin/pip" install -q nc-gcode-interpreter || say "nc-gcode-interpreter did not install; row skipped"
fi

cat >"$PEERS/node/cncjs-run.js" <<'EOF'
// Reads an RS274 file with cncjs's gcode-toolpath and counts the motion segments.
const Toolpath = require("gcode-toolpath");
let lines = 0, arcs = 0;
const toolpath = new Toolpath({ addLine: () => { lines++; }, addArcCurve: () => { arcs++; } });
toolpath.loadFromFile(process.argv[2], (err) => {
  if (err) { console.error(err); process.exit(1); }
  console.log(`${lines} lines, ${arcs} arcs`);
});
EOF
cat >"$PEERS/ncgi-run.py" <<'EOF'
# Reads a Sinumerik file with nc-gcode-interpreter (into a Polars DataFrame).
import sys
import nc_gcode_interpreter as nc
with open(sys.argv[1]) as f:
    df, state = nc.nc_to_dataframe(f)
print(len(df), "rows")
EOF

# --- programs and binary -------------------------------------------------------------------
gen() {
  local dialect=$1 ext=$2 path="$PROGRAMS/mill3_${BLOCKS}.$2"
  [ -s "$path" ] || { python3 "$GEN" --kind mill3 --blocks "$BLOCKS" --dialect "$dialect" >"$path.tmp" && mv "$path.tmp" "$path"; }
  echo "$path"
}
MPF="$(gen sinumerik mpf)"
NGC="$(gen rs274 ngc)"
if [ -z "${NCTWIN_BIN:-}" ]; then
  say "building nctwin (release)"
  cargo build --release -q -p nctwin-server
fi
NCTWIN="${NCTWIN_BIN:-${CARGO_TARGET_DIR:-$ROOT/target}/release/nctwin}"

# Each row: name, dialect, command. A row whose tool is missing is skipped.
names=() cmds=()
add() { names+=("$1"); cmds+=("$2"); }
add "nctwin interpret" "$NCTWIN simulate --machine mill-3axis --interpret-only --compact $MPF"
add "nctwin simulate" "$NCTWIN simulate --machine mill-3axis --compact $MPF"
command -v rs274 >/dev/null && add "linuxcnc rs274" "rs274 -g $NGC $PEERS/rs274-out.txt"
[ -d "$PEERS/node/node_modules/gcode-toolpath" ] && add "cncjs gcode-toolpath" "node $PEERS/node/cncjs-run.js $NGC"
"$PEERS/venv/bin/python" -c 'import nc_gcode_interpreter' 2>/dev/null &&
  add "nc-gcode-interpreter" "$PEERS/venv/bin/python $PEERS/ncgi-run.py $MPF"

# Sanity: every command runs and ends well once (and gives its peak RSS).
RESULTS="$PEERS/results.tsv"
: >"$RESULTS"
say "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in "${!names[@]}"; do
  say "${names[$i]}"
  rss_kib="$(python3 - "${cmds[$i]}" <<'EOF'
import resource, shlex, subprocess, sys
r = subprocess.run(shlex.split(sys.argv[1]), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
if r.returncode != 0:
    sys.exit(f"exit {r.returncode}: {r.stderr[-500:]}{r.stdout[-300:]}")
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
EOF
  )" || { say "${names[$i]} failed; skipped"; continue; }
  if command -v hyperfine >/dev/null; then
    hyperfine -N --runs "$RUNS" --warmup 0 --style none --export-json "$PEERS/hf.json" "${cmds[$i]}" >/dev/null 2>&1 ||
      hyperfine --runs "$RUNS" --style none --export-json "$PEERS/hf.json" "${cmds[$i]}" >/dev/null
    median="$(python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["results"][0]; print(r["median"], r["user"] + r["system"])' "$PEERS/hf.json")"
  else
    median="$(python3 - "$RUNS" "${cmds[$i]}" <<'EOF'
import resource, shlex, statistics, subprocess, sys, time
times = []
for _ in range(int(sys.argv[1])):
    t = time.perf_counter()
    subprocess.run(shlex.split(sys.argv[2]), stdout=subprocess.DEVNULL, check=True)
    times.append(time.perf_counter() - t)
ru = resource.getrusage(resource.RUSAGE_CHILDREN)
print(statistics.median(times), (ru.ru_utime + ru.ru_stime) / len(times))
EOF
    )"
  fi
  read -r wall cpu <<<"$median"
  printf '%s\t%s\t%s\t%s\n' "${names[$i]}" "$wall" "$cpu" "$rss_kib" >>"$RESULTS"
done
say "load after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$RESULTS" "$BLOCKS" "$RUNS" <<'EOF'
import sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1]) if l.strip()]
blocks, runs = int(sys.argv[2]), sys.argv[3]
rows = [(n, float(t), float(c), int(r)) for n, t, c, r in rows]
peers = [r for r in rows if not r[0].startswith("nctwin")]
best = min(peers, key=lambda r: r[1]) if peers else None
print(f"\nmill3, {blocks:,} blocks (RS274 file for rs274/cncjs, Sinumerik file for NCTwin and nc-gcode-interpreter);"
      f" whole process, median of {runs}")
best_cpu = min(peers, key=lambda r: r[2]) if peers else None
head = (f'{"":24} {"wall s":>8} {"blocks/s":>12} {"vs best":>8}   {"CPU s":>8} {"blocks/CPU-s":>13} {"vs best":>8}'
        f' {"peak RSS MB":>12}')
print(head)
print("-" * len(head))
for n, t, c, r in rows:
    ratio = f"{best[1] / t:.2f}x" if best else "-"
    ratio_cpu = f"{best_cpu[2] / c:.2f}x" if best_cpu and c > 0 else "-"
    print(f"{n:24} {t:8.3f} {blocks / t:12,.0f} {ratio:>8}   {c:8.3f} {blocks / c if c > 0 else 0:13,.0f} {ratio_cpu:>8}"
          f" {r / 1024:12.1f}")
if best:
    print(f"\nbest peer by wall time: {best[0]}, by CPU time: {best_cpu[0]}; 'vs best' = the best peer's time / this"
          " row's time (>1: faster than the best peer). CPU = user + system (mean of the runs).")
EOF
