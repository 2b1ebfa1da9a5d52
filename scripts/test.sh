#!/usr/bin/env bash
# The test command of the README: install dependencies, build, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
scripts/build.sh
scripts/build-web.sh                  # the browser explorer (WebAssembly engine, web/dist)
export OSCIDRUM_WEB_REQUIRED=1        # its tests fail, not skip, without web/dist
ctest --test-dir build --output-on-failure -j "$(nproc)"
