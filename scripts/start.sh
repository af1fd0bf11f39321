#!/usr/bin/env bash
# Starts NCTwin with the browser HMI: builds web/dist when needed, then the server (release).
# Arguments go to the server, e.g. scripts/start.sh --bind 0.0.0.0:8080 --data-dir /var/lib/nctwin
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
bash scripts/build-web.sh --if-stale
exec cargo run --release -p nctwin-server -- "$@"
