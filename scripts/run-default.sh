#!/usr/bin/env bash
# The main job of the README: install dependencies, build, and run the default case (the paper's
# roller on Table 2 soil at G = 25 MN/m^2, mu = 0.5) into out/default/: the steady state as CSV,
# a JSON summary, the event list and the plots.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
scripts/build.sh
out=out/default
mkdir -p "$out"
export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
build/apps/cli/oscidrum run --csv "$out/steady_state.csv" --json "$out/summary.json" \
  --events "$out/events.csv" --plot "$out/plots"
echo "outputs in $out/ (steady_state.csv, summary.json, events.csv, plots/)" >&2
