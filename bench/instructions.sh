#!/usr/bin/env bash
# Instructions executed by a study (valgrind's callgrind): a count that does not change with the
# machine's load, where the CPU time of the 2-core machines scatters by some 10 % between runs of
# the same binary. Compare two builds of the same study: the count follows the work done (not the
# latency of divisions or of dependent chains, which only time shows), so a change is shown by
# both, the count and alternating timed runs (bench/README.md).
#   bench/instructions.sh [OSCIDRUM_BINARY [STUDY.toml]]
#     (defaults: build/apps/cli/oscidrum, bench/sweep/product.toml: about 3 minutes)
# Prints the total, the number of cases and the instructions per case; with PROFILE=1 the
# functions' own shares too (callgrind_annotate). Needs valgrind (apt-get install valgrind).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/apps/cli/oscidrum}
study=${2:-$here/sweep/product.toml}
if ! command -v valgrind >/dev/null; then
  echo "bench/instructions.sh: valgrind is not installed (apt-get install valgrind)" >&2
  exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$bin" sweep "$study" -j1 \
  --out "$tmp/r.csv" --quiet 2>"$tmp/log"
total=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/log")
cases=$(($(wc -l <"$tmp/r.csv") - 1))
printf 'instructions %s, cases %d, per case %.3g\n' "$total" "$cases" \
  "$(echo "$total / $cases" | bc -l)"
if [[ ${PROFILE:-0} == 1 ]]; then
  callgrind_annotate "$tmp/cg.out" 2>/dev/null | sed -n '/file:function/,$p' | head -25
fi
