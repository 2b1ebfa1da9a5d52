#!/usr/bin/env bash
# Peak memory (maximum resident set size) of `oscidrum sweep` against its number of cases: the
# study of bench/sweep/memory.toml cut to N cases by its contact.mu axis. The sweep's memory must
# not grow with the number of cases (rows wait on disk, cases are built when they run).
#   bench/sweep_memory.sh [OSCIDRUM_BINARY]     (default build/apps/cli/oscidrum)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/apps/cli/oscidrum}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| cases | peak memory (max RSS) | wall time |\n|---:|---:|---:|\n'
for num in 5 50 500; do
  sed "s/num = 500/num = $num/" "$here/sweep/memory.toml" >"$tmp/study.toml"
  /usr/bin/time -f '%M %e' -o "$tmp/time" "$bin" sweep "$tmp/study.toml" --out "$tmp/r.csv" \
    --threads 2 --quiet || true
  read -r kb seconds < <(tail -n 1 "$tmp/time")
  printf '| %d | %.0f MB | %s s |\n' $((400 * num)) "$(echo "$kb / 1024" | bc -l)" "$seconds"
done
