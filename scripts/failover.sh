#!/usr/bin/env bash
# The cluster failover test: a throwaway cluster (scripts/cluster.sh: PostgreSQL, three nodes,
# HAProxy), then tools/loadgen's nctwin-failover through the proxy: FAILOVER_SESSIONS real-time
# sessions with a WebSocket viewer each, FAILOVER_CYCLES times kill -9 of the node holding the
# most sessions, time until each of its sessions serves again through the proxy (p50, p99),
# every acknowledged write read back, the dead node's sessions checked (program, machine data,
# mode, positions; a running program stopped at its block), the node started again.
# Fails when a write is lost, a session comes back wrong or late, or p99 exceeds 10 s.
#
#   scripts/failover.sh                FAILOVER_SESSIONS=300 FAILOVER_CYCLES=20
#   FAILOVER_CYCLES=3 scripts/failover.sh
#
# scripts/test.sh runs it (with the cycles that fit CI, see there). Builds the debug binaries.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
SESSIONS="${FAILOVER_SESSIONS:-300}"
CYCLES="${FAILOVER_CYCLES:-20}"
TARGET="${CARGO_TARGET_DIR:-$ROOT/target}/debug"

# One package per build: each keeps the feature set (and the artifacts) of its own builds.
cargo build -q -p nctwin-server
cargo build -q -p nctwin-loadgen
# 300 viewers, the proxy's two sides of each, the nodes' database and client connections.
ulimit -n 65536 2>/dev/null || ulimit -n "$(ulimit -Hn)"

NCTWIN_CLUSTER_DIR="$(mktemp -d "${TMPDIR:-/tmp}/nctwin-failover.XXXXXX")/cluster"
export NCTWIN_CLUSTER_DIR NCTWIN_BIN="$TARGET/nctwin"
stop() {
  bash "$ROOT/scripts/cluster.sh" stop >/dev/null || true
  rmdir "$(dirname "$NCTWIN_CLUSTER_DIR")" 2>/dev/null || true
}
trap stop EXIT
bash "$ROOT/scripts/cluster.sh" start
# shellcheck source=/dev/null
source "$NCTWIN_CLUSTER_DIR/cluster.env"
started=$SECONDS
if ! "$TARGET/nctwin-failover" --url "http://127.0.0.1:$NCTWIN_PROXY_PORT" --cluster "$ROOT/scripts/cluster.sh" \
  --sessions "$SESSIONS" --cycles "$CYCLES" ${FAILOVER_JSON:+--json}; then
  for node in n1 n2 n3; do
    echo "---- last lines of node $node's log ----" >&2
    tail -n 15 "$NCTWIN_CLUSTER_DIR/$node.log" >&2 || true
  done
  exit 1
fi
echo "failover test: $((SECONDS - started)) s for $CYCLES cycles"
