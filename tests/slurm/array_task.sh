#!/usr/bin/env bash
# One task of the Slurm job array that tests/slurm/job_array.sh submits: `iblbake batch` with no --shard,
# so the shard comes from SLURM_ARRAY_TASK_ID/MIN/COUNT, every event (--json) appended to a log named by
# the task and its run (SLURM_RESTART_COUNT: 0, then 1 after a requeue).
#
# Arguments: IBLBAKE MANIFEST CACHE EVENTS_DIR PAUSE_TASK. The first run of task PAUSE_TASK freezes its
# bake (SIGSTOP) as soon as its second item starts, then says so with EVENTS_DIR/paused: the test then
# cancels the task while it is provably mid-run (one item finished, one started and unfinished) instead of
# hoping a timed scancel lands between two items.
set -euo pipefail
iblbake=$1 manifest=$2 cache=$3 events_dir=$4 pause_task=$5
run="task-${SLURM_ARRAY_TASK_ID}-run-${SLURM_RESTART_COUNT:-0}"
"$iblbake" batch "$manifest" --cache "$cache" --jobs 1 --json >"$events_dir/$run.jsonl" &
bake=$!
echo "$bake" >"$events_dir/$run.pid"
if [ "$SLURM_ARRAY_TASK_ID" = "$pause_task" ] && [ "${SLURM_RESTART_COUNT:-0}" = 0 ]; then
  # The events are flushed line by line; polled every 10 ms, while one tiny item takes far longer to bake.
  until [ "$(grep -c '"event":"item-start"' "$events_dir/$run.jsonl")" -ge 2 ]; do
    kill -0 "$bake" 2>/dev/null || exit 1 # the bake ended before its second item: nothing to pause
    sleep 0.01
  done
  kill -STOP "$bake"
  touch "$events_dir/paused"
fi
wait "$bake"
