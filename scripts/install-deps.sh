#!/usr/bin/env bash
# Installs what a fresh Debian machine (with Rust, Node/npm, Python and apt) lacks for the tests:
# Debian's Chromium for the browser test, Debian's postgresql for the PostgreSQL storage tests,
# the HMI's npm packages (web/) and the browser test's (tests/browser), and a Python venv (.venv,
# git-ignored) with schemathesis for the API bad-input campaign (scripts/fuzz-api.sh). Idempotent.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

if [ ! -x /usr/bin/chromium ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "==> installing chromium (apt)"
  $SUDO apt-get update
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends chromium
else
  echo "==> chromium present: $(/usr/bin/chromium --version 2>/dev/null || echo /usr/bin/chromium)"
fi

# PostgreSQL server binaries (initdb, pg_ctl) for the PostgreSQL storage tests: scripts/test.sh
# starts a throwaway cluster of its own; the package's default cluster is not used.
if ! ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 && ! command -v initdb >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "==> installing postgresql (apt)"
  $SUDO apt-get update
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends postgresql
else
  echo "==> postgresql present: $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | head -n 1)"
fi

echo "==> npm ci (web)"
(cd "$ROOT/web" && npm ci --no-audit --no-fund)

echo "==> npm ci (tests/browser)"
cd "$ROOT/tests/browser"
npm ci --no-audit --no-fund

# Pinned so a CI run tests what was tested here; bump deliberately.
SCHEMATHESIS_VERSION=4.32.5
if [ ! -x "$ROOT/.venv/bin/schemathesis" ] ||
  [ "$("$ROOT/.venv/bin/schemathesis" --version 2>/dev/null)" != "schemathesis, version $SCHEMATHESIS_VERSION" ]; then
  echo "==> python venv with schemathesis $SCHEMATHESIS_VERSION (.venv)"
  python3 -m venv "$ROOT/.venv"
  "$ROOT/.venv/bin/pip" install --quiet --disable-pip-version-check "schemathesis==$SCHEMATHESIS_VERSION"
else
  echo "==> schemathesis $SCHEMATHESIS_VERSION present in .venv"
fi
