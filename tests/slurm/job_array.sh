#!/usr/bin/env bash
# `iblbake batch` as a job array on a real Slurm (issue 17): a single-node cluster of Debian's slurm-wlm
# (slurmctld, slurmd) and munge, configured and started here with every config, key, socket, spool, state
# and log file under WORK_DIR, and stopped on any exit. A 3-task array (--array=1-3, so the index is
# SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) bakes a 6-item manifest over one shared cache; task 2 is
# frozen after its first item (tests/slurm/array_task.sh), cancelled (scancel) and requeued (scontrol
# requeue). Checks: every task completes; the products are byte-identical to a local unsharded run; across
# every run's events each item was baked ("ok") exactly once; the cancelled run had finished its first item
# and not its second, and the requeued run reported the first up to date and baked the second.
#
# Usage: job_array.sh IBLBAKE WORK_DIR. Needs root (slurmd starts jobs as their user) and the Slurm and
# munge binaries (.ci/install-deps installs them): without them the test fails, it does not skip.
set -euo pipefail
iblbake=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
fail() {
  echo "slurm job array: FAIL: $*" >&2
  exit 1
}
for tool in munged mungekey slurmctld slurmd sbatch scancel scontrol squeue sinfo oiiotool; do
  command -v "$tool" >/dev/null ||
    fail "'$tool' not found: install Debian's slurm-wlm, munge and openimageio-tools (.ci/install-deps)"
done
[ "$(id -u)" = 0 ] || fail "needs root: slurmd runs each job as the user who submitted it"

# A run that CTest killed on its timeout left its daemons behind; their pid files are in our own work dir.
for daemon in slurmctld slurmd munged; do
  if [ -f "$work/run/$daemon.pid" ] && [ "$(cat "/proc/$(cat "$work/run/$daemon.pid")/comm" 2>/dev/null)" = "$daemon" ]; then
    kill "$(cat "$work/run/$daemon.pid")" && sleep 1
  fi
done
rm -rf "$work"
mkdir -p "$work"/{key,run,state,spool,log,farm/events,local}
# munged refuses a key readable by others and a socket directory others cannot search.
chmod 700 "$work/key"
chmod 755 "$work" "$work/run"
cd "$work"

job=""
stop_daemons() {
  local status=$?
  trap - EXIT
  set +e
  [ -n "$job" ] && scancel "$job" 2>/dev/null
  [ -f run/slurmctld.pid ] && scontrol shutdown >/dev/null 2>&1 # stops slurmctld and slurmd
  for daemon in slurmctld slurmd munged; do
    [ -f "run/$daemon.pid" ] || continue
    local pid
    pid=$(cat "run/$daemon.pid")
    kill "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
    rm -f "run/$daemon.pid"
  done
  [ "$status" != 0 ] && tail -n 20 log/*.log >&2
  exit "$status"
}
trap stop_daemons EXIT

# --- the cluster ---------------------------------------------------------------------------------------
mungekey --create --keyfile="$work/key/munge.key"
munged --socket="$work/run/munge.socket" --key-file="$work/key/munge.key" --pid-file="$work/run/munged.pid" \
  --log-file="$work/log/munged.log" --seed-file="$work/key/munged.seed"
node=$(hostname -s)
# No cgroups, no systemd, no accounting database: process tracking by parent pid, no task plugin. The
# ports are not the defaults, so a Slurm already on the machine is left alone.
cat >slurm.conf <<EOF
ClusterName=iblbake-test
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$work/run/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
KillWait=2
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 300); do
  [ "$(sinfo -h -n "$node" -o %t 2>/dev/null)" = idle ] && break
  sleep 0.1
done
[ "$(sinfo -h -n "$node" -o %t)" = idle ] || fail "node $node did not become idle (log/slurmd.log)"

# --- the batch: 6 HDRI items (32x16 lat-longs, 16-texel faces, draft) -----------------------------------
items=() patterns=()
for i in 0 1 2 3 4 5; do
  patterns+=(--pattern "fill:top=0.$i,0.5,1:bottom=1,0.$i,0.2" 32x16 3 -d float -o "farm/env$i.hdr")
  items+=("{\"hdri\": \"env$i.hdr\", \"id\": \"sky$i\", \"output\": \"out/sky$i\", \"preset\": \"draft\", \"faceSize\": 16}")
done
oiiotool "${patterns[@]}" # one run: oiiotool takes seconds to start on a busy machine
(IFS=,; echo "{\"items\": [${items[*]}]}") >farm/batch.json
cp farm/batch.json farm/env*.hdr local/

# --- the job array; task 2 (shard 2/3: sky1, sky4) is cancelled mid-run and requeued --------------------
job=$(sbatch --parsable --array=1-3 --cpus-per-task=1 --requeue --open-mode=append -o "$work/log/task-%a.out" \
  "$here/array_task.sh" "$iblbake" "$work/farm/batch.json" "$work/cache" "$work/farm/events" 2)
for _ in $(seq 600); do
  [ -f farm/events/paused ] || [ -z "$(squeue -h -j "${job}_2")" ] && break # paused, or ended without
  sleep 0.1
done
[ -f farm/events/paused ] || fail "task 2 did not reach its second item: $(tail -n 3 log/task-2.out)"
[ -f farm/out/sky1/manifest.json ] || fail "task 2 paused before finishing sky1"
[ ! -e farm/out/sky4/manifest.json ] || fail "task 2 paused after finishing sky4: not mid-run"
scancel "${job}_2"
paused_bake=$(cat farm/events/task-2-run-0.pid)
for _ in $(seq 100); do kill -0 "$paused_bake" 2>/dev/null || break; sleep 0.1; done
! kill -0 "$paused_bake" 2>/dev/null || fail "the cancelled bake (pid $paused_bake) still runs"
for _ in $(seq 100); do
  scontrol show job "${job}_2" | grep -q 'JobState=CANCELLED' && break
  sleep 0.1
done
scontrol requeue "${job}_2"
# Slurm holds a requeued job for about two minutes (its EligibleTime); this makes it eligible now.
scontrol update JobId="${job}_2" StartTime=now
for _ in $(seq 900); do [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break; sleep 0.1; done
[ -z "$(squeue -h -j "$job")" ] || fail "the job array did not finish in 90 s"
states=$(scontrol show job "$job" | grep -o 'JobState=[A-Z]*\|ExitCode=[0-9:]*' | tr '\n' ' ')
[ "$(scontrol show job "$job" | grep -c 'JobState=COMPLETED')" = 3 ] || fail "not every task completed: $states"
[ "$(scontrol show job "$job" | grep -c 'ExitCode=0:0')" = 3 ] || fail "a task exited non-zero: $states"

# --- the same batch, unsharded, on this machine: byte-identical products ---------------------------------
"$iblbake" batch local/batch.json --shard 1/1 --cache local/cache --quiet
[ "$(find local/out -name manifest.json | wc -l)" = 6 ] || fail "the local run did not bake 6 items"
diff -r farm/out local/out >&2 || fail "the job array's products differ from the local run's"

# --- each item baked once; the cancelled task's second item finished by its requeue ----------------------
item_ends() { # item-end events of the given logs as "id status" lines
  cat "$@" | grep '"event":"item-end"' | sed -E 's/.*"item":"([^"]*)".*"status":"([^"]*)".*/\1 \2/'
}
baked=$(item_ends farm/events/*.jsonl | grep ' ok$' | sort | tr '\n' ' ')
[ "$baked" = "sky0 ok sky1 ok sky2 ok sky3 ok sky4 ok sky5 ok " ] || fail "items baked (ok) over all runs: $baked"
[ "$(ls farm/events/*.jsonl | xargs -n1 basename | tr '\n' ' ')" = \
  "task-1-run-0.jsonl task-2-run-0.jsonl task-2-run-1.jsonl task-3-run-0.jsonl " ] ||
  fail "unexpected runs: $(ls farm/events)"
[ "$(item_ends farm/events/task-2-run-0.jsonl | tr '\n' ' ')" = "sky1 ok " ] ||
  fail "the cancelled run did not end exactly sky1"
grep -q '"event":"item-start","index":4,"item":"sky4"' farm/events/task-2-run-0.jsonl ||
  fail "the cancelled run had not started sky4"
[ "$(item_ends farm/events/task-2-run-1.jsonl | tr '\n' ' ')" = "sky1 up-to-date sky4 ok " ] ||
  fail "the requeued run did not skip sky1 and bake sky4: $(item_ends farm/events/task-2-run-1.jsonl)"
echo "slurm job array: 3 tasks completed (task 2 cancelled mid-run and requeued), 6 items baked once each," \
  "products identical to the local run"
