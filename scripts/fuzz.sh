#!/usr/bin/env bash
# The fuzz suite (tests/fuzz/) run longer than in CI: SCALE times the draws of each class, with a
# new seed (printed first, so that a failure can be rerun with OSCIDRUM_FUZZ_SEED=<seed>).
# Usage: scripts/fuzz.sh [SCALE] [SEED]      (after scripts/build.sh; default SCALE 20)
set -euo pipefail
cd "$(dirname "$0")/.."
export OSCIDRUM_FUZZ_SCALE="${1:-20}"
export OSCIDRUM_FUZZ_SEED="${2:-$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}"
echo "fuzz: seed $OSCIDRUM_FUZZ_SEED, $OSCIDRUM_FUZZ_SCALE x the default draws"
build/tests/fuzz/test_fuzz_cli
if [ -x "$(command -v /usr/bin/python3)" ] && [ -d build/python ]; then
  PYTHONPATH=build/python /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python/test_fuzz.py
fi
