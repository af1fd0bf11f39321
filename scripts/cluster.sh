#!/usr/bin/env bash
# A throwaway NCTwin cluster on this machine: a PostgreSQL server (scripts/postgres.sh, Unix
# socket only), three `nctwin` nodes n1, n2, n3 on that database and HAProxy in front of them
# (deploy/haproxy.cfg). README "A cluster of nodes" explains the layout and its production
# equivalent.
#
#   scripts/cluster.sh start          starts everything, prints the ports (clients use the proxy's)
#   scripts/cluster.sh stop           stops everything and removes the cluster's directory
#   scripts/cluster.sh status         what runs
#   scripts/cluster.sh kill NODE      kill -9 of node n1|n2|n3 (as a crash would)
#   scripts/cluster.sh restart NODE   starts a killed node again (same name, same port)
#
# Environment: NCTWIN_CLUSTER_DIR (default /tmp/nctwin-cluster: pids, logs, the proxy's map and
# `cluster.env` with the ports), NCTWIN_BIN (default: target/debug/nctwin, built if missing),
# LEASE_SECONDS (default: nctwin's), PROXY_PORT (default: a free port).
# Needs haproxy and PostgreSQL's initdb/pg_ctl (scripts/install-deps.sh installs both).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DIR="${NCTWIN_CLUSTER_DIR:-/tmp/nctwin-cluster}"
NODES=(n1 n2 n3)
STARTUP_TIMEOUT_S=60

# shellcheck source=scripts/postgres.sh
source "$ROOT/scripts/postgres.sh"

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

node_index() {
  case "$1" in
    n1) echo 0 ;; n2) echo 1 ;; n3) echo 2 ;;
    *) echo "unknown node '$1' (n1, n2 or n3)" >&2; return 1 ;;
  esac
}

alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

# Starts node $1 (its port and the database from cluster.env) and waits until it listens.
start_node() {
  local node=$1 port
  # shellcheck source=/dev/null
  source "$DIR/cluster.env"
  port="$(eval echo "\$NCTWIN_PORT_$node")"
  local lease=()
  [ -n "${LEASE_SECONDS:-}" ] && lease=(--lease-seconds "$LEASE_SECONDS")
  mkdir -p "$DIR/$node"
  # Behind the proxy every client has the proxy's address: the per-address limits would cap
  # the whole cluster's clients, so they are raised to the node's totals here.
  NO_COLOR=1 "$NCTWIN_BIN" --bind "127.0.0.1:$port" --database "$NCTWIN_DATABASE" --node-id "$node" \
    "${lease[@]}" --data-dir "$DIR/$node" --web-dir "$ROOT/web/dist" \
    --allow-host "127.0.0.1:$NCTWIN_PROXY_PORT" --allow-host "localhost:$NCTWIN_PROXY_PORT" \
    --allow-origin "http://127.0.0.1:$NCTWIN_PROXY_PORT" --allow-origin "http://localhost:$NCTWIN_PROXY_PORT" \
    --max-sessions-per-ip 1000 --max-connections-per-ip 20000 \
    >>"$DIR/$node.log" 2>&1 &
  echo $! >"$DIR/$node.pid"
  for _ in $(seq $((STARTUP_TIMEOUT_S * 20))); do
    if grep -q "listening on http://" "$DIR/$node.log" 2>/dev/null &&
      [ "$(grep -c "listening on http://" "$DIR/$node.log")" -ge "$(cat "$DIR/$node.starts" 2>/dev/null || echo 1)" ]; then
      return 0
    fi
    if ! alive "$DIR/$node.pid"; then
      echo "error: node $node exited; its log:" >&2
      tail -n 30 "$DIR/$node.log" >&2
      return 1
    fi
    sleep 0.05
  done
  echo "error: node $node is not listening after ${STARTUP_TIMEOUT_S} s" >&2
  return 1
}

cmd_start() {
  if [ -f "$DIR/cluster.env" ]; then
    echo "error: a cluster runs in $DIR already (scripts/cluster.sh stop first)" >&2
    exit 1
  fi
  command -v haproxy >/dev/null || { echo "error: haproxy not found (scripts/install-deps.sh)" >&2; exit 1; }
  if [ -z "${NCTWIN_BIN:-}" ]; then
    NCTWIN_BIN="${CARGO_TARGET_DIR:-$ROOT/target}/debug/nctwin"
    [ -x "$NCTWIN_BIN" ] || (cd "$ROOT" && cargo build -q -p nctwin-server)
  fi
  mkdir -p "$DIR"
  pg_test_start >"$DIR/postgres.out"
  if [ -z "${NCTWIN_TEST_POSTGRES_URL:-}" ]; then
    cat "$DIR/postgres.out" >&2
    echo "error: no PostgreSQL server could be started (scripts/install-deps.sh)" >&2
    rm -rf "$DIR"
    exit 1
  fi
  local proxy_port="${PROXY_PORT:-$(free_port)}"
  {
    echo "NCTWIN_BIN='$NCTWIN_BIN'"
    echo "NCTWIN_DATABASE='$NCTWIN_TEST_POSTGRES_URL'"
    echo "PG_TEST_DIR='$PG_TEST_DIR'"
    echo "NCTWIN_PROXY_PORT=$proxy_port"
    for node in "${NODES[@]}"; do echo "NCTWIN_PORT_$node=$(free_port)"; done
  } >"$DIR/cluster.env"
  for node in "${NODES[@]}"; do start_node "$node"; done
  # shellcheck source=/dev/null
  source "$DIR/cluster.env"
  : >"$DIR/holders.map"
  NCTWIN_PROXY_BIND="127.0.0.1:$NCTWIN_PROXY_PORT" NCTWIN_HOLDERS_MAP="$DIR/holders.map" \
    NCTWIN_N1="127.0.0.1:$NCTWIN_PORT_n1" NCTWIN_N2="127.0.0.1:$NCTWIN_PORT_n2" NCTWIN_N3="127.0.0.1:$NCTWIN_PORT_n3" \
    haproxy -D -f "$ROOT/deploy/haproxy.cfg" -p "$DIR/haproxy.pid" 2>"$DIR/haproxy.log" || {
    cat "$DIR/haproxy.log" >&2
    cmd_stop
    exit 1
  }
  # The proxy answers once its health checks found the nodes up.
  for _ in $(seq 100); do
    if python3 -c 'import sys, urllib.request; urllib.request.urlopen(sys.argv[1], timeout=1)' \
      "http://127.0.0.1:$NCTWIN_PROXY_PORT/api/v1/health" 2>/dev/null; then break; fi
    sleep 0.1
  done
  echo "PostgreSQL: $NCTWIN_DATABASE"
  for node in "${NODES[@]}"; do
    echo "node $node: http://127.0.0.1:$(eval echo "\$NCTWIN_PORT_$node") (pid $(cat "$DIR/$node.pid"), log $DIR/$node.log)"
  done
  echo "proxy (HAProxy): http://127.0.0.1:$NCTWIN_PROXY_PORT  <- clients and the HMI use this one"
  echo "state: $DIR/cluster.env; stop with: scripts/cluster.sh stop"
}

cmd_stop() {
  [ -d "$DIR" ] || { echo "no cluster in $DIR"; return 0; }
  if alive "$DIR/haproxy.pid"; then kill "$(cat "$DIR/haproxy.pid")" 2>/dev/null || true; fi
  local node
  for node in "${NODES[@]}"; do
    if alive "$DIR/$node.pid"; then kill "$(cat "$DIR/$node.pid")" 2>/dev/null || true; fi
  done
  for node in "${NODES[@]}"; do
    for _ in $(seq 100); do alive "$DIR/$node.pid" || break; sleep 0.1; done
    if alive "$DIR/$node.pid"; then kill -9 "$(cat "$DIR/$node.pid")" 2>/dev/null || true; fi
  done
  if [ -f "$DIR/cluster.env" ]; then
    # shellcheck source=/dev/null
    source "$DIR/cluster.env"
    if [ "$(id -u)" -eq 0 ]; then PG_TEST_RUNAS=(runuser -u postgres --); fi
    pg_test_stop
  fi
  rm -rf "$DIR"
  echo "cluster stopped"
}

cmd_status() {
  [ -f "$DIR/cluster.env" ] || { echo "no cluster in $DIR"; return 0; }
  cat "$DIR/cluster.env"
  local node
  for node in "${NODES[@]}" haproxy; do
    if alive "$DIR/$node.pid"; then echo "$node: running (pid $(cat "$DIR/$node.pid"))"; else echo "$node: not running"; fi
  done
}

cmd_kill() {
  node_index "$1" >/dev/null
  alive "$DIR/$1.pid" || { echo "error: node $1 is not running" >&2; exit 1; }
  kill -9 "$(cat "$DIR/$1.pid")"
  wait "$(cat "$DIR/$1.pid")" 2>/dev/null || true
}

cmd_restart() {
  node_index "$1" >/dev/null
  if alive "$DIR/$1.pid"; then echo "error: node $1 is running" >&2; exit 1; fi
  echo $(($(grep -c "listening on http://" "$DIR/$1.log") + 1)) >"$DIR/$1.starts"
  start_node "$1"
}

case "${1:-}" in
  start) cmd_start ;;
  stop) cmd_stop ;;
  status) cmd_status ;;
  kill) cmd_kill "${2:?node}" ;;
  restart) cmd_restart "${2:?node}" ;;
  *) echo "usage: $0 start|stop|status|kill NODE|restart NODE" >&2; exit 2 ;;
esac
