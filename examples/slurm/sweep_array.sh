#!/usr/bin/env bash
# A study on a Slurm cluster: one array task per shard, then one job that merges the shards.
#
#   sbatch --export=ALL,STUDY=examples/table2_sweep.toml,OUT=results examples/slurm/sweep_array.sh
#
# Each task runs `oscidrum sweep STUDY --shard I/N` on the cores Slurm gives it and writes
# OUT/shard_I.csv; when every task has ended, a dependent job runs `oscidrum merge`, which
# writes OUT/results.csv, the rows one unsharded `oscidrum sweep` writes (byte for byte when the
# cases are independent, --no-continuation; and refuses to merge if a shard is missing,
# duplicated or from another study). A task that is killed (time limit, preemption) keeps its
# finished cases in OUT/shard_I.csv.journal: resubmit that task with
# `sbatch --array=I --export=ALL,SHARDS=N,...` (an array of one task counts 1, so N must be
# given) and it resumes. N is SHARDS, else the array's largest task id.
#SBATCH --job-name=oscidrum-sweep
#SBATCH --array=1-8
#SBATCH --cpus-per-task=4
#SBATCH --time=01:00:00
#SBATCH --output=oscidrum-sweep-%A_%a.log
set -euo pipefail

OSCIDRUM=${OSCIDRUM:-oscidrum}         # the binary (e.g. build/apps/cli/oscidrum)
STUDY=${STUDY:?set STUDY=path/to/study.toml}
OUT=${OUT:-results}
# The number of shards: SHARDS, else the array's largest index (--array=1-N). Not the array's
# task count, which is 1 for a resubmitted task (--array=3 made it shard 3/1).
N=${SHARDS:-${SLURM_ARRAY_TASK_MAX:?run this script with sbatch --array=1-N, or set SHARDS=N}}
I=${SLURM_ARRAY_TASK_ID}
mkdir -p "$OUT"

resume=()
if [ -e "$OUT/shard_$I.csv.journal" ]; then resume=(--resume); fi
# The first task queues the merge, to run when every task of the array has ended. Exit code 1
# (some case not steady) still writes the shard; a task that wrote nothing makes the merge fail
# with "shards missing".
if [ "$I" = "${SLURM_ARRAY_TASK_MIN:-1}" ]; then
  sbatch --dependency="afterany:${SLURM_ARRAY_JOB_ID}" --job-name=oscidrum-merge \
    --output="$OUT/merge.log" \
    --wrap="$OSCIDRUM merge $OUT/shard_*.csv --out $OUT/results.csv"
fi

status=0
"$OSCIDRUM" sweep "$STUDY" --shard "$I/$N" --out "$OUT/shard_$I.csv" \
  --threads "${SLURM_CPUS_PER_TASK:-0}" --quiet "${resume[@]}" || status=$?
exit $status
