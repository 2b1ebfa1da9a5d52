#!/usr/bin/env bash
# What --hdf5 costs a sweep: wall time and peak memory of the study of bench/sweep/hdf5.toml
# (2000 cases) with and without --hdf5, on one and two threads, and the size of the file.
#   bench/sweep_hdf5.sh [OSCIDRUM_BINARY]     (default build/apps/cli/oscidrum)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/apps/cli/oscidrum}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| threads | output | wall time | peak memory (max RSS) | HDF5 file |\n|---:|---|---:|---:|---:|\n'
for threads in 1 2; do
  for hdf5 in no yes; do
    rm -f "$tmp"/r.*
    extra=()
    if [ "$hdf5" = yes ]; then extra=(--hdf5 "$tmp/r.h5"); fi
    /usr/bin/time -f '%M %e' -o "$tmp/time" "$bin" sweep "$here/sweep/hdf5.toml" --out "$tmp/r.csv" \
      --threads "$threads" --quiet "${extra[@]}" || true
    read -r kb seconds < <(tail -n 1 "$tmp/time")
    size="-"
    if [ "$hdf5" = yes ]; then size="$(du -m "$tmp/r.h5" | cut -f1) MB"; fi
    printf '| %d | %s | %s s | %.0f MB | %s |\n' "$threads" \
      "$([ "$hdf5" = yes ] && echo "--out and --hdf5" || echo "--out")" "$seconds" \
      "$(echo "$kb / 1024" | bc -l)" "$size"
  done
done
