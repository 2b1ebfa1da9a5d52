#!/usr/bin/env bash
# A screenshot of the browser explorer, e.g. the README's picture (docs/img/explorer.png):
#   scripts/screenshot-web.sh [URL-query] [out.png]
#   scripts/screenshot-web.sh "" docs/img/explorer.png            # the default case
#   scripts/screenshot-web.sh "G=40&mu=0.3&MMd=0.05" case.png     # any case the URL can hold
# Builds web/dist if needed (scripts/build-web.sh), serves it on 127.0.0.1, opens the page in
# headless Chromium (OSCIDRUM_CHROMIUM, default /usr/bin/chromium) and waits for the page's ready
# marker (<body data-ready="true">, set once the first case is shown) before writing the PNG
# (default explorer.png). A plain `chromium --headless --screenshot` would capture "loading the
# engine...": the engine loads and runs in a Web Worker after the page itself has loaded.
set -euo pipefail
# OSCIDRUM_WEB_DIST: serve another build of the explorer (default web/dist, built if missing).
here=$(cd "$(dirname "$0")/.." && pwd)
dist=${OSCIDRUM_WEB_DIST:-$here/web/dist}
if [ -z "${OSCIDRUM_WEB_DIST:-}" ] && { [ ! -f "$dist/oscidrum.wasm" ] || [ ! -d "$here/web/node_modules/playwright-core" ]; }; then
  "$here/scripts/build-web.sh"
fi
exec node "$here/web/screenshot.js" "${1:-}" "${2:-explorer.png}" --dist "$dist"
