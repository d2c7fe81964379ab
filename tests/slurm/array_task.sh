#!/usr/bin/env bash
# One task of the Slurm job array that tests/slurm/job_array.sh submits: `iblbake batch` with no --shard,
# so the shard comes from SLURM_ARRAY_TASK_ID/MIN/COUNT, every event (--json) appended to a log named by
# the task and its run (SLURM_RESTART_COUNT: 0, then 1 after a requeue).
#
# Arguments: IBLBAKE MANIFEST CACHE EVENTS_DIR PAUSE_TASK. The first run of task PAUSE_TASK freezes its
# bake (SIGSTOP) as soon as its second item starts, then says so with EVENTS_DIR/paused: the test then
# cancels the task while it is provably mid-run (one item finished, one started and unfinished) instead of
# hoping a timed scancel lands between two items. The events come through a FIFO read line by line, so the
# stop follows the second item's start within a read, not a poll: one tiny item bakes in about 0.1 s on the
# CPU backend, well inside a 10 ms poll's reach on a loaded machine.
set -euo pipefail
iblbake=$1 manifest=$2 cache=$3 events_dir=$4 pause_task=$5
run="task-${SLURM_ARRAY_TASK_ID}-run-${SLURM_RESTART_COUNT:-0}"
events="$events_dir/$run.jsonl"
fifo="$events_dir/$run.fifo"
rm -f "$fifo"
mkfifo "$fifo"
"$iblbake" batch "$manifest" --cache "$cache" --jobs 1 --json >"$fifo" &
bake=$!
echo "$bake" >"$events_dir/$run.pid"
pause=0
if [ "$SLURM_ARRAY_TASK_ID" = "$pause_task" ] && [ "${SLURM_RESTART_COUNT:-0}" = 0 ]; then pause=1; fi
starts=0
while IFS= read -r line; do
  printf '%s\n' "$line" >>"$events"
  if [ "$pause" = 1 ] && [[ $line == *'"event":"item-start"'* ]]; then
    starts=$((starts + 1))
    if [ "$starts" -ge 2 ]; then
      kill -STOP "$bake"
      touch "$events_dir/paused"
    fi
  fi
done <"$fifo"
# The paused run never gets here (the test cancels it while its bake is stopped); a bake that ended before
# its second item left nothing to pause, which the test reports.
wait "$bake"
