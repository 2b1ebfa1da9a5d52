#!/usr/bin/env bash
# Instructions executed (valgrind's callgrind): a count that does not change with the machine's
# load, where the CPU time of the 2-core machines scatters by some 10 % between runs of the same
# binary. Compare two builds of the same work: the count follows the work done (not the latency
# of divisions or of dependent chains, which only time shows), so a change is shown by both, the
# count and alternating timed runs (bench/README.md).
#   bench/instructions.sh [OSCIDRUM_BINARY [STUDY.toml]]
#     a study (defaults: build/apps/cli/oscidrum, bench/sweep/product.toml: about 3 minutes);
#     prints the total, the number of cases and the instructions per case; with PROFILE=1 the
#     functions' own shares too (callgrind_annotate).
#   bench/instructions.sh --from-rest [BENCH_SIMULATE_BINARY]
#     the cases from rest of the performance issue's target 2 (bench_simulate's
#     BM_Method_StickSlip_Shooting and BM_Method_Rolling_R0606_Shooting; default
#     build/bench/bench_simulate): the instructions of one call of oscidrum::simulate each;
#     with PROFILE=1 the functions' inclusive shares too (callgrind_annotate --inclusive=yes).
# Needs valgrind (apt-get install valgrind).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if ! command -v valgrind >/dev/null; then
  echo "bench/instructions.sh: valgrind is not installed (apt-get install valgrind)" >&2
  exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [[ ${1:-} == --from-rest ]]; then
  bin=${2:-$here/../build/bench/bench_simulate}
  for case in StickSlip Rolling_R0606; do
    # A minimum time far below one iteration's: the benchmark runs exactly one iteration.
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
      --toggle-collect='oscidrum::simulate(*' "$bin" \
      --benchmark_filter="^BM_Method_${case}_Shooting\$" --benchmark_min_time=0.000001 \
      --benchmark_format=json >"$tmp/bench.json" 2>"$tmp/log"
    total=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/log")
    iterations=$(sed -n 's/.*"iterations": \([0-9]*\).*/\1/p' "$tmp/bench.json" | head -1)
    printf '%s from rest: instructions per case %.4g (%s iteration(s))\n' "$case" \
      "$(echo "$total / $iterations" | bc -l)" "$iterations"
    if [[ ${PROFILE:-0} == 1 ]]; then
      callgrind_annotate --inclusive=yes "$tmp/cg.out" 2>/dev/null | sed -n '/file:function/,$p' |
        grep 'oscidrum::' | head -30
    fi
  done
  exit 0
fi

bin=${1:-$here/../build/apps/cli/oscidrum}
study=${2:-$here/sweep/product.toml}
valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$bin" sweep "$study" -j1 \
  --out "$tmp/r.csv" --quiet 2>"$tmp/log"
total=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/log")
cases=$(($(wc -l <"$tmp/r.csv") - 1))
printf 'instructions %s, cases %d, per case %.3g\n' "$total" "$cases" \
  "$(echo "$total / $cases" | bc -l)"
if [[ ${PROFILE:-0} == 1 ]]; then
  callgrind_annotate "$tmp/cg.out" 2>/dev/null | sed -n '/file:function/,$p' | head -25
fi
