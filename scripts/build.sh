#!/usr/bin/env bash
# Configure and build oscidrum (library, CLI, Python module, tests) into build/.
# Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DOSCIDRUM_WERROR=ON \
  -DOSCIDRUM_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3 "$@" >/dev/null
cmake --build build -j "$(nproc)"
