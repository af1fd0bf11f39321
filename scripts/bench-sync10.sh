#!/usr/bin/env bash
# The cost of ten active synchronized actions (README, figures): the 200k-block mill3 program
# in fast pace without and with the ten actions of scripts/sync10.mpf prepended, side by side
# for each binary given (default: this worktree's release build), CPU seconds per run, and
# whether the end states (the `state` of the JSON) are the same for every binary.
#
#   scripts/bench-sync10.sh [BINARY...]      RUNS=3 by default
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
GEN="${GEN_PROGRAM:-$ROOT/../shared/bench/gen_program.py}"
[ -f "$GEN" ] || GEN=/work/shared/bench/gen_program.py
RUNS="${RUNS:-3}"
BINS=("$@")
[ ${#BINS[@]} -eq 0 ] && BINS=("$ROOT/target/release/nctwin")
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
python3 "$GEN" --blocks 200000 --kind mill3 > "$TMP/plain.mpf"
cat "$ROOT/scripts/sync10.mpf" "$TMP/plain.mpf" > "$TMP/sync10.mpf"

cpu() { python3 -c 'import json,sys; print("%.2f" % json.load(sys.stdin)["cpu_time_s"])'; }
state() { python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)["state"], sort_keys=True))'; }

for run in $(seq "$RUNS"); do
  for case in plain sync10; do
    for bin in "${BINS[@]}"; do
      out="$("$bin" simulate --machine mill-3axis --compact "$TMP/$case.mpf" || true)"
      echo "$out" | state > "$TMP/state-$case-$(basename "$bin")"
      printf 'run %s  %-7s %-28s %s s\n' "$run" "$case" "$(basename "$bin")" "$(echo "$out" | cpu)"
    done
  done
done
for case in plain sync10; do
  first=""
  for bin in "${BINS[@]}"; do
    f="$TMP/state-$case-$(basename "$bin")"
    if [ -z "$first" ]; then first="$f"; elif cmp -s "$first" "$f"; then echo "$case: end state of $(basename "$bin") the same"; else echo "$case: end state of $(basename "$bin") DIFFERS"; fi
  done
done
