#!/usr/bin/env bash
# Peak memory (maximum resident set size) of `oscidrum sweep` against its number of cases: the
# study of bench/sweep/memory.toml cut to N cases by its contact.mu axis. The sweep's memory must
# not grow with the number of cases (rows wait on disk, cases are built when they run), up to a
# million cases (num = 2500; about 3 minutes on two cores). Then the same for --list and --resume
# of the million-case study (the resume after a kill half-way).
#   bench/sweep_memory.sh [OSCIDRUM_BINARY]     (default build/apps/cli/oscidrum)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/apps/cli/oscidrum}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| cases | peak memory (max RSS) | wall time |\n|---:|---:|---:|\n'
for num in 5 50 500 2500; do
  sed "s/num = 500/num = $num/" "$here/sweep/memory.toml" >"$tmp/study.toml"
  /usr/bin/time -f '%M %e' -o "$tmp/time" "$bin" sweep "$tmp/study.toml" --out "$tmp/r.csv" \
    --threads 2 --quiet || true
  read -r kb seconds < <(tail -n 1 "$tmp/time")
  printf '| %d | %.0f MB | %s s |\n' $((400 * num)) "$(echo "$kb / 1024" | bc -l)" "$seconds"
done

sed "s/num = 500/num = 2500/" "$here/sweep/memory.toml" >"$tmp/study.toml"
/usr/bin/time -f '%M %e' -o "$tmp/time" "$bin" sweep "$tmp/study.toml" --list >/dev/null
read -r kb seconds < <(tail -n 1 "$tmp/time")
printf '| 1000000, --list | %.0f MB | %s s |\n' "$(echo "$kb / 1024" | bc -l)" "$seconds"
rm -f "$tmp/r.csv" "$tmp/r.csv.journal"
"$bin" sweep "$tmp/study.toml" --out "$tmp/r.csv" --threads 2 --quiet &
pid=$!
sleep 60
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
done_rows=$(($(wc -l <"$tmp/r.csv.journal") - 1))
/usr/bin/time -f '%M %e' -o "$tmp/time" "$bin" sweep "$tmp/study.toml" --out "$tmp/r.csv" \
  --threads 2 --quiet --resume || true
read -r kb seconds < <(tail -n 1 "$tmp/time")
printf '| 1000000, --resume after %d | %.0f MB | %s s |\n' "$done_rows" "$(echo "$kb / 1024" | bc -l)" \
  "$seconds"
