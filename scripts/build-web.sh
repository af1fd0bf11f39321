#!/usr/bin/env bash
# Builds the browser HMI (web/ → web/dist/, which the server serves at /): npm ci when
# web/node_modules is missing or older than the lock file, then the type check and vite build.
#
#   scripts/build-web.sh            type check + build
#   scripts/build-web.sh --if-stale build only when a source is newer than web/dist
set -euo pipefail

WEB="$(cd "$(dirname "${BASH_SOURCE[0]}")/../web" && pwd)"
cd "$WEB"

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules ]; then
  echo "==> npm ci (web)"
  npm ci --no-audit --no-fund
  touch node_modules
fi

if [ "${1:-}" = "--if-stale" ] && [ -f dist/index.html ] &&
  [ -z "$(find index.html src package-lock.json vite.config.ts tsconfig.json -newer dist/index.html -print -quit)" ]; then
  exit 0
fi

echo "==> tsc --noEmit (web)"
npx --no-install tsc --noEmit
echo "==> vite build (web)"
npx --no-install vite build --logLevel warn
