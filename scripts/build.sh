#!/usr/bin/env bash
# Configure and build oscidrum (library, CLI, Python module, tests) into build/, then install the
# Python package for /usr/bin/python3 (into its dist-packages) so that `import oscidrum` works.
# Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DOSCIDRUM_WERROR=ON \
  -DOSCIDRUM_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3 "$@" >/dev/null
cmake --build build -j "$(nproc)"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
$SUDO cmake --install build --component python >/dev/null
