#!/usr/bin/env bash
# Installs what a fresh Debian machine (with Rust, Node/npm, Python and apt) lacks for the tests:
# Debian's Chromium for the browser test, the HMI's npm packages (web/) and the browser test's
# (tests/browser). Idempotent.
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

echo "==> npm ci (web)"
(cd "$ROOT/web" && npm ci --no-audit --no-fund)

echo "==> npm ci (tests/browser)"
cd "$ROOT/tests/browser"
npm ci --no-audit --no-fund
