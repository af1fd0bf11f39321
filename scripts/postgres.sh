# Sourced by scripts/test.sh: a throwaway PostgreSQL server for the storage tests.
#
#   pg_test_start   creates a cluster in a new temp dir (initdb), starts it listening on a Unix
#                   socket in that dir only (no TCP port), exports NCTWIN_TEST_POSTGRES_URL.
#                   Without initdb/pg_ctl (Debian's postgresql package) it prints a note and
#                   returns 0: the PostgreSQL tests then skip themselves; under CI=true that is
#                   an error instead, so CI cannot silently skip them.
#   pg_test_stop    stops the server and removes the temp dir (safe to call twice; test.sh calls
#                   it from its EXIT trap).
#
# initdb refuses to run as root: as root the cluster is created and run by the `postgres` user
# (which the Debian package creates), through runuser.

PG_TEST_DIR=""
PG_TEST_RUNAS=()

pg_test_find_bin() {
  local dir
  if command -v initdb >/dev/null 2>&1 && command -v pg_ctl >/dev/null 2>&1; then
    dirname "$(command -v initdb)"
    return 0
  fi
  for dir in $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V -r); do
    if [ -x "$dir/initdb" ] && [ -x "$dir/pg_ctl" ]; then
      echo "$dir"
      return 0
    fi
  done
  return 1
}

pg_test_start() {
  local bin
  if ! bin="$(pg_test_find_bin)"; then
    if [ "${CI:-}" = true ]; then
      echo "error: no initdb/pg_ctl found; CI must run the PostgreSQL storage tests (scripts/install-deps.sh installs postgresql)" >&2
      return 1
    fi
    echo "note: no initdb/pg_ctl found (Debian package postgresql): the PostgreSQL storage tests will be skipped"
    return 0
  fi
  PG_TEST_DIR="$(mktemp -d /tmp/nctwin-pg.XXXXXX)"
  chmod 755 "$PG_TEST_DIR"
  if [ "$(id -u)" -eq 0 ]; then
    if ! id postgres >/dev/null 2>&1; then
      echo "note: running as root and there is no postgres user for initdb: PostgreSQL storage tests skipped"
      rm -rf "$PG_TEST_DIR"
      PG_TEST_DIR=""
      return 0
    fi
    chown postgres: "$PG_TEST_DIR"
    PG_TEST_RUNAS=(runuser -u postgres --)
  fi
  "${PG_TEST_RUNAS[@]}" "$bin/initdb" -D "$PG_TEST_DIR/data" -U nctwin --auth=trust -E UTF8 --no-locale \
    >"$PG_TEST_DIR/initdb.log" 2>&1 || {
    cat "$PG_TEST_DIR/initdb.log" >&2
    return 1
  }
  # Unix socket only, in the temp dir; fsync stays on (the default), as in production.
  "${PG_TEST_RUNAS[@]}" "$bin/pg_ctl" -D "$PG_TEST_DIR/data" -l "$PG_TEST_DIR/server.log" -w -t 60 \
    -o "-c listen_addresses='' -c unix_socket_directories='$PG_TEST_DIR' -c max_connections=200" start \
    >/dev/null || {
    cat "$PG_TEST_DIR/server.log" >&2
    return 1
  }
  local host
  host="$(printf '%s' "$PG_TEST_DIR" | sed 's#/#%2F#g')"
  export NCTWIN_TEST_POSTGRES_URL="postgres://nctwin@$host/postgres"
  echo "PostgreSQL $("$bin/postgres" --version | awk '{print $3}') started for the tests: $NCTWIN_TEST_POSTGRES_URL"
}

pg_test_stop() {
  if [ -n "$PG_TEST_DIR" ]; then
    local bin
    bin="$(pg_test_find_bin)" || true
    if [ -n "$bin" ] && [ -f "$PG_TEST_DIR/data/postmaster.pid" ]; then
      "${PG_TEST_RUNAS[@]}" "$bin/pg_ctl" -D "$PG_TEST_DIR/data" -m immediate -w stop >/dev/null 2>&1 || true
    fi
    rm -rf "$PG_TEST_DIR"
    PG_TEST_DIR=""
  fi
  unset NCTWIN_TEST_POSTGRES_URL
}
