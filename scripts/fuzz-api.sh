#!/usr/bin/env bash
# Bad-input campaign: schemathesis generates requests from the server's own OpenAPI document
# (/api/v1/openapi.json) and fails on any 5xx and on any response that does not match the
# document (status code, content type, headers, body schema); then
# scripts/fuzz_deep_expressions.py sends expressions thousands of levels deep or long in every
# field that takes program text (a few seconds), and scripts/fuzz_nc_requests.py programs of the
# newer language with I/O and machine data changed while they run (FUZZ_NC_ROUNDS sessions, 40).
# A panic in the server's log fails the campaign too.
#
#   scripts/fuzz-api.sh              about 100 generated cases per operation, fixed seed
#   FUZZ_EXAMPLES=500 scripts/fuzz-api.sh
#   FUZZ_SEED=random scripts/fuzz-api.sh
#
# Starts the debug build of `nctwin` on a free port with a temporary data directory. Needs the
# venv that scripts/install-deps.sh creates (.venv with schemathesis).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

ST="$ROOT/.venv/bin/schemathesis"
TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
EXAMPLES="${FUZZ_EXAMPLES:-100}"
SEED="${FUZZ_SEED:-20261122}"
STARTUP_TIMEOUT_S=60

if [ ! -x "$ST" ]; then
  echo "error: $ST not found; run scripts/install-deps.sh first" >&2
  exit 1
fi

cargo build -p nctwin-server

DATA_DIR="$(mktemp -d "${TMPDIR:-/tmp}/nctwin-fuzz-data.XXXXXX")"
LOG="$(mktemp "${TMPDIR:-/tmp}/nctwin-fuzz-server.XXXXXX.log")"
REPORT="$(mktemp -d "${TMPDIR:-/tmp}/nctwin-fuzz-report.XXXXXX")"
SERVER_PID=""

cleanup() {
  if [ -n "$SERVER_PID" ]; then
    kill "$SERVER_PID" 2>/dev/null || true
    wait "$SERVER_PID" 2>/dev/null || true
  fi
  rm -rf "$DATA_DIR"; [ -n "${FUZZ_KEEP_REPORT:-}" ] || rm -rf "$REPORT"
  rm -f "$LOG"
}
trap cleanup EXIT

# Generous limits: the fuzzer creates many sessions from one address and sends commands to
# one session back to back (the limits themselves are tested by server/tests/limits.rs).
NO_COLOR=1 RUST_LOG=info "$TARGET_DIR/debug/nctwin" --bind 127.0.0.1:0 --data-dir "$DATA_DIR" \
  --max-sessions 100000 --max-sessions-per-ip 100000 --commands-per-second 100000 --command-burst 100000 \
  >"$LOG" 2>&1 &
SERVER_PID=$!

URL=""
for _ in $(seq $((STARTUP_TIMEOUT_S * 10))); do
  URL="$(grep -oE 'listening on http://[^[:space:]"]+' "$LOG" | head -n 1 | sed -E 's/^listening on //')" || true
  [ -n "$URL" ] && break
  if ! kill -0 "$SERVER_PID" 2>/dev/null; then
    echo "error: the server exited before it was listening" >&2
    cat "$LOG" >&2
    exit 1
  fi
  sleep 0.1
done
if [ -z "$URL" ]; then
  echo "error: no 'listening on http://' line within ${STARTUP_TIMEOUT_S} s" >&2
  cat "$LOG" >&2
  exit 1
fi
SEED_ARGS=(--seed "$SEED")
[ "$SEED" = random ] && SEED_ARGS=()

# Zero 5xx and every response as documented: status code, content type, headers, body schema.
CHECKS=not_a_server_error,status_code_conformance,content_type_conformance,response_headers_conformance,response_schema_conformance

campaign() {
  local name="$1"
  shift
  echo "==> schemathesis ($name) against $URL: ${EXAMPLES} cases per operation, seed $SEED"
  local status=0
  SCHEMATHESIS_HOOKS=schemathesis_hooks PYTHONPATH="$ROOT/scripts${PYTHONPATH:+:$PYTHONPATH}" \
    "$ST" "$@" run "$URL/api/v1/openapi.json" \
    --checks "$CHECKS" \
    --max-examples "$EXAMPLES" "${SEED_ARGS[@]}" \
    --generation-database none \
    --request-timeout 30 \
    --workers 2 \
    --no-color \
    --report ndjson --report-dir "$REPORT/$name" "${EXTRA_ARGS[@]}" || status=$?
  if [ "$status" -ne 0 ]; then
    echo "error: schemathesis ($name) found problems (exit $status); server log:" >&2
    tail -n 40 "$LOG" >&2
    exit "$status"
  fi
}

# 1. Everything generated, session ids included (mostly unknown: the 404 paths and every
#    malformed body, query and header).
EXTRA_ARGS=()
campaign random-ids

# 2. Every operation on one live session, so generated bodies reach the channel (programs,
#    MDA, JOG, machine data, stored programs). Deleting it would end the campaign early.
SESSION="$(curl -sf -X POST "$URL/api/v1/sessions" | sed -E 's/^\{"id":"([^"]+)".*/\1/')"
CONFIG="$REPORT/live-session.toml"
printf '[parameters]\n"path.id" = "%s"\n' "$SESSION" >"$CONFIG"
EXTRA_ARGS=(--exclude-operation-id delete_session)
campaign live-session --config-file "$CONFIG"

# 3. Deep and long expressions in every field that takes program text (schemathesis does not
#    build them): each answered with alarm 12080, no 5xx, the server alive after each.
if ! python3 "$ROOT/scripts/fuzz_deep_expressions.py" "$URL"; then
  echo "error: deep expressions: server log:" >&2
  tail -n 40 "$LOG" >&2
  exit 1
fi
# 4. Cross-site requests (issue 20): a page of another site, a rebound host name and a body
#    sent as a form must be refused before they reach a session.
expect_status() {
  local want="$1" what="$2"
  shift 2
  local got
  got="$(curl -s -o /dev/null -w '%{http_code}' "$@")"
  if [ "$got" != "$want" ]; then
    echo "error: $what: expected $want, got $got" >&2
    exit 1
  fi
}
PORT="${URL##*:}"
expect_status 403 "POST from another origin" -X POST -H 'origin: http://evil.example' "$URL/api/v1/sessions/$SESSION/reset"
expect_status 403 "WebSocket from another origin" -H 'origin: http://evil.example' -H 'connection: upgrade' \
  -H 'upgrade: websocket' -H 'sec-websocket-version: 13' -H 'sec-websocket-key: dGhlIHNhbXBsZSBub25jZQ==' \
  "$URL/api/v1/sessions/$SESSION/stream"
expect_status 403 "a rebound host name" -H "host: evil.example:$PORT" "$URL/api/v1/machines"
expect_status 415 "a JSON body sent as text/plain" -X POST -H 'content-type: text/plain' \
  -d '{"program":"M30"}' "$URL/api/v1/sessions/$SESSION/run"
expect_status 200 "the server's own origin" -X POST -H "origin: $URL" "$URL/api/v1/sessions/$SESSION/reset"
echo "==> cross-site requests refused"

# 5. NC-aware requests: sessions with resized synchronized-action memory and I/O, programs of
#    the newer language, I/O and machine data changed while they run.
if ! python3 "$ROOT/scripts/fuzz_nc_requests.py" "$URL" "${FUZZ_NC_ROUNDS:-40}"; then
  echo "error: NC requests: server log:" >&2
  tail -n 40 "$LOG" >&2
  exit 1
fi

# An engine that panics ends its session and the client sees a 404 ("has ended"), which the
# checks above accept for a session they did not create: the log says it.
if grep -q "panicked" "$LOG"; then
  echo "error: the engine panicked during the campaign:" >&2
  grep -B2 -A12 "panicked" "$LOG" | head -n 60 >&2
  exit 1
fi

if ! kill -0 "$SERVER_PID" 2>/dev/null; then
  echo "error: the server died during the campaign" >&2
  cat "$LOG" >&2
  exit 1
fi
echo "==> schemathesis: no 5xx, every response matches the OpenAPI document"
