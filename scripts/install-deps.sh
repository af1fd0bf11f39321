#!/usr/bin/env bash
# Installs what a fresh Debian machine (with Rust, Node/npm, Python and apt) lacks for the tests;
# scripts/test.sh calls it first, so a fresh clone needs no other command. Idempotent, and a fast
# no-op when everything is there (it checks files and their dates; it runs no package manager then):
#   - Debian packages (apt, as root or through sudo): chromium (the browser test), postgresql
#     (initdb/pg_ctl for the PostgreSQL storage tests and the cluster), haproxy (the cluster's
#     proxy, scripts/cluster.sh and the failover test);
#   - the HMI's npm packages (web/) and the browser test's (tests/browser): `npm ci` when
#     node_modules is missing or package-lock.json changed since the last install;
#   - a Python venv (.venv, git-ignored) with schemathesis for the API bad-input campaign
#     (scripts/fuzz-api.sh).
#
#   scripts/install-deps.sh            everything
#   scripts/install-deps.sh rust       only what `scripts/test.sh rust` needs (the apt packages)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WHAT="${1:-all}"

# --- Debian packages: one apt run for all that are missing -------------------------------------
missing=()
[ -x /usr/bin/chromium ] || [ "$WHAT" = rust ] || missing+=(chromium)
# PostgreSQL server binaries (initdb, pg_ctl): scripts/postgres.sh starts a throwaway cluster of
# its own; the package's default cluster is not used.
if ! ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 && ! command -v initdb >/dev/null 2>&1; then
  missing+=(postgresql)
fi
command -v haproxy >/dev/null 2>&1 || [ -x /usr/sbin/haproxy ] || missing+=(haproxy)
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "==> installing ${missing[*]} (apt)"
  $SUDO apt-get update
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi
[ "$WHAT" = rust ] && exit 0

# --- npm packages ------------------------------------------------------------------------------
# `npm ci` when node_modules is missing or package-lock.json is newer than npm's record of the
# last install (node_modules/.package-lock.json, which `npm ci` writes): a pull that changed
# the lock file installs again.
npm_ci() {
  local dir=$1
  if [ "$dir/node_modules/.package-lock.json" -nt "$dir/package-lock.json" ]; then
    return 0
  fi
  echo "==> npm ci (${dir#"$ROOT"/})"
  (cd "$dir" && npm ci --no-audit --no-fund)
}
npm_ci "$ROOT/web"
npm_ci "$ROOT/tests/browser"

# --- Python venv with schemathesis ---------------------------------------------------------------
# Pinned so a CI run tests what was tested here; bump deliberately.
SCHEMATHESIS_VERSION=4.32.5
if ! ls -d "$ROOT"/.venv/lib/python3*/site-packages/schemathesis-"$SCHEMATHESIS_VERSION".dist-info >/dev/null 2>&1 ||
  [ ! -x "$ROOT/.venv/bin/schemathesis" ]; then
  echo "==> python venv with schemathesis $SCHEMATHESIS_VERSION (.venv)"
  python3 -m venv "$ROOT/.venv"
  "$ROOT/.venv/bin/pip" install --quiet --disable-pip-version-check "schemathesis==$SCHEMATHESIS_VERSION"
fi
