#!/usr/bin/env bash
# Build the browser explorer (scripts/build-web.sh) and serve it on 127.0.0.1 (prints the URL).
# Usage: scripts/web.sh [PORT]   (default 8039). Works offline once built. Ctrl-C stops it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build-web.sh
exec node web/serve.js --port "${1:-8039}"
