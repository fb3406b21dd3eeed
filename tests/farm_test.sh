#!/usr/bin/env bash
# tests/farm_test.sh VKSKY: the render farm of docs/sequences.md, run for real (issue 30). On this machine, a Slurm
# cluster of one node (Debian's slurm-wlm and munge: munged, slurmctld and slurmd started here as root, their state,
# spool, logs and key under a temporary directory, on free ports) renders a 40-frame 320x180 sequence (EXR + PNG)
# with the job script shipped in tools/farm, and with its GNU parallel variant:
#  1. sbatch --array=0-3: four tasks, a quarter each. Task 2 is cancelled with scancel once it has written its first
#     frame: what it leaves are whole frames only (each file equals the single-process render's, no temp file).
#  2. sbatch --array=2 (the same script and arguments; the script resumes with --skip-existing) completes the range
#     without rendering again the frames it finished: its summary counts them as skipped, their files keep their inodes.
#     The 80 files are then the single-process render's, byte for byte.
#  3. tools/farm/vksky-parallel.sh 4: the same 80 files.
#  4. Nothing is left running: every daemon it started is stopped (also on failure or interrupt: trap), and no
#     process has its working directory or command line under the test's directory.
# Every render runs under the validation layer with synchronization validation (VKSKY_VALIDATION=1, passed on to the
# Slurm tasks by sbatch); any message fails the render and so the test. Not root and no passwordless sudo: SKIP (77);
# CI runs as root and never skips. Bounded: about 40 s on 2 shared cores; ctest's limit is 90 s.
set -u
VKSKY=$(realpath "${1:?usage: farm_test.sh VKSKY}")
SRC=$(cd "$(dirname "$0")/.." && pwd)
if [ "$(id -u)" -ne 0 ]; then
    if sudo -n true 2>/dev/null; then exec sudo -n -E "$0" "$VKSKY"; fi
    echo "SKIP: the Slurm daemons (slurmctld, slurmd, munged) need root: not root and no passwordless sudo"
    exit 77
fi
export PATH="$PATH:/usr/sbin:/sbin"
for tool in munged munge slurmctld slurmd sbatch scancel squeue scontrol sinfo parallel; do
    command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (tools/debian-packages.txt: slurm-wlm munge parallel)" >&2; exit 1; }
done
export VKSKY VKSKY_VALIDATION=1
unset SLURM_JOB_ID SLURM_ARRAY_TASK_ID   # a test run inside a Slurm job must not read as one of our tasks
start_s=$SECONDS
work=$(mktemp -d /tmp/vksky-farm.XXXXXX)
chmod 755 "$work"   # munged wants its socket's directory searchable by all
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
munged_pid='' ctld_pid='' slurmd_pid=''

# Stops what this test started: jobs first (a step outlives slurmd), then the daemons by their process ids.
stop_all() {
    if [ -n "$ctld_pid" ] && kill -0 "$ctld_pid" 2>/dev/null; then
        scancel --quiet --full --user=root 2>/dev/null
        for _ in $(seq 100); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 0.1; done
        scontrol shutdown >/dev/null 2>&1
    fi
    for pid in $slurmd_pid $ctld_pid $munged_pid; do kill -TERM "$pid" 2>/dev/null; done
    for pid in $slurmd_pid $ctld_pid $munged_pid; do
        for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
    done
    munged_pid='' ctld_pid='' slurmd_pid=''
}
# The processes with their working directory or command line under $work (a task or a step left behind).
leftovers() {
    local p cmd
    for p in /proc/[0-9]*; do
        [ "${p#/proc/}" = $$ ] || [ "${p#/proc/}" = "$BASHPID" ] && continue   # this test and the subshell asking
        cmd=$(tr '\0' ' ' 2>/dev/null <"$p/cmdline")
        if [[ $(readlink "$p/cwd" 2>/dev/null) == "$work"* || $cmd == *"$work"* ]]; then echo "${p#/proc/} $cmd"; fi
    done
}
# A watchdog ends the test (its EXIT trap stops the daemons) before ctest's limit would kill it outright.
( trap 'kill "$sleeper" 2>/dev/null; exit 0' TERM
  sleep 80 & sleeper=$!
  wait "$sleeper" && echo "FAIL: the farm test ran 80 s; stopping it" >&2 && kill -TERM $$ ) &
watchdog=$!
trap 'kill "$watchdog" 2>/dev/null; wait "$watchdog" 2>/dev/null; stop_all; rm -rf "$work"' EXIT
trap 'exit 1' INT TERM

# A TCP port nobody listens on (ctest may run other tests; a developer's machine may run a Slurm of its own).
free_port() {
    local p
    for _ in $(seq 50); do
        p=$((20000 + RANDOM % 40000))
        (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
    done
    echo 0
}

# The cluster: munge's key and socket, a slurm.conf of one node (this host; 4 CPUs declared so that the 4 tasks run
# at once whatever the machine has), state and spool here.
D=$work/slurm
mkdir -p "$D/state" "$D/spool" "$D/log" "$work/logs"
head -c 1024 /dev/urandom >"$D/munge.key" && chmod 400 "$D/munge.key"
cat >"$D/slurm.conf" <<EOF
ClusterName=vksky-farm-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge.sock
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=5
MinJobAge=600
NodeName=farmnode NodeAddr=127.0.0.1 CPUs=4 State=UNKNOWN
PartitionName=farm Nodes=farmnode Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$D/slurm.conf
grep -q 'Port=0$' "$SLURM_CONF" && { echo "FAIL: no free TCP port found" >&2; exit 1; }
# In the foreground, as this shell's children: their ids are known, and stop_all ends exactly them.
munged -F -f --socket="$D/munge.sock" --key-file="$D/munge.key" --pid-file="$D/munged.pid" \
    --log-file="$D/log/munged.log" --seed-file="$D/munged.seed" >"$D/log/munged.out" 2>&1 &
munged_pid=$!
for _ in $(seq 100); do munge -S "$D/munge.sock" -n >/dev/null 2>&1 && break; sleep 0.1; done
munge -S "$D/munge.sock" -n >/dev/null 2>&1 || { echo "FAIL: munged did not start: $(tail -3 "$D/log/munged.log")" >&2; exit 1; }
slurmctld -D -f "$SLURM_CONF" >"$D/log/slurmctld.out" 2>&1 &
ctld_pid=$!
slurmd -D -f "$SLURM_CONF" -N farmnode >"$D/log/slurmd.out" 2>&1 &
slurmd_pid=$!
for _ in $(seq 200); do [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && break; sleep 0.1; done
[ "$(sinfo -h -o %T 2>/dev/null)" = idle ] || { echo "FAIL: the node is not idle: $(sinfo 2>&1; tail -5 "$D"/log/*.log)" >&2; exit 1; }
echo "farm: cluster up in $((SECONDS - start_s)) s"

# Waits until job $1 has left the queue (at most $2 s).
wait_job() {
    for _ in $(seq $(($2 * 10))); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0; sleep 0.1; done
    fail "job $1 still queued after $2 s: $(squeue 2>&1)"
    return 1
}
# A task's state and exit code as scontrol shows them ("COMPLETED 0:0").
task_state() { scontrol -o show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).* ExitCode=\([0-9:]*\).*/\1 \2/p'; }

# RGB named (--spectral 0): under auto this twilight-to-afternoon run renders spectral (32g, 8 passes a frame).
SEQ=(--width 320 --height 180 --animate sun-elevation=-3:25 --animate yaw=0:60 --frame-count 40 --spectral 0
     --render 'f_%04d.exr' --render 'f_%04d.png')
mkdir "$work/whole" "$work/farm" "$work/par"
(cd "$work/whole" && "$VKSKY" "${SEQ[@]}" 2>"$work/logs/whole.err") || fail "the single-process render failed: $(tail -3 "$work/logs/whole.err")"
[ "$(ls "$work/whole" | wc -l)" -eq 80 ] || fail "the single-process render wrote $(ls "$work/whole" | wc -l) files; expected 80"
echo "farm: single-process render at $((SECONDS - start_s)) s"

# 1. The array, task 2 cancelled once its first frame (both files) is written. The test's own directory is not the
# tasks' (sbatch --chdir), as on a farm.
cd "$D" || exit 1
job=$(sbatch --parsable --array=0-3 --chdir="$work/farm" --output="$work/logs/%A_%a.log" \
    "$SRC/tools/farm/vksky-array.sbatch" 4 "${SEQ[@]}") || { echo "FAIL: sbatch refused the array" >&2; exit 1; }
for _ in $(seq 600); do [ -e "$work/farm/f_0020.png" ] && break; sleep 0.05; done
scancel "${job}_2" || fail "scancel ${job}_2 failed"
[ -e "$work/farm/f_0020.png" ] || fail "task 2 wrote no frame in 30 s: $(cat "$work/logs/${job}_2.log")"
wait_job "$job" 60
echo "farm: array done at $((SECONDS - start_s)) s"
for t in 0 1 3; do
    [ "$(task_state "${job}_$t")" = "COMPLETED 0:0" ] || fail "task $t ended $(task_state "${job}_$t"): $(tail -3 "$work/logs/${job}_$t.log")"
    grep -q '^vksky: 10 frames rendered, 0 skipped (written before); LUTs computed 1 time$' "$work/logs/${job}_$t.log" \
        || fail "task $t's summary: $(tail -1 "$work/logs/${job}_$t.log")"
done
[[ $(task_state "${job}_2") == CANCELLED* ]] || fail "task 2 ended $(task_state "${job}_2"); expected CANCELLED"
# Only whole frames: every file there is the single-process render's file of that name; no temp file.
for f in "$work/farm"/* "$work/farm"/.[!.]*; do
    [ -e "$f" ] || continue
    cmp -s "$f" "$work/whole/${f##*/}" || fail "after the cancel, ${f##*/} is not a whole frame of the sequence"
done
whole_frames=() inodes=()
for i in $(seq 20 29); do
    e=$work/farm/f_00$i.exr p=$work/farm/f_00$i.png
    [ -e "$e" ] && [ -e "$p" ] && whole_frames+=("$i") && inodes+=("$(stat -c %i "$e") $(stat -c %i "$p")")
done
n=${#whole_frames[@]}
[ "$n" -ge 1 ] && [ "$n" -le 9 ] || fail "task 2 left $n whole frames of 10; expected a cancel mid-range (1 to 9)"
echo "farm: task 2 cancelled after $n whole frames"

# 2. Task 2 resubmitted: the same script and arguments.
job2=$(sbatch --parsable --array=2 --chdir="$work/farm" --output="$work/logs/%A_%a.log" \
    "$SRC/tools/farm/vksky-array.sbatch" 4 "${SEQ[@]}") || fail "sbatch refused the resubmission"
wait_job "$job2" 60
log2=$work/logs/${job2}_2.log
[ "$(task_state "${job2}_2")" = "COMPLETED 0:0" ] || fail "the resubmitted task ended $(task_state "${job2}_2"): $(tail -3 "$log2")"
grep -q "^vksky: $((10 - n)) frames\{0,1\} rendered, $n skipped (written before); LUTs computed [01] times\{0,1\}$" "$log2" \
    || fail "the resubmitted task's summary: '$(tail -1 "$log2")'; expected $((10 - n)) rendered, $n skipped"
for k in "${!whole_frames[@]}"; do
    i=${whole_frames[$k]}
    grep -q "^vksky: frame $i (.*skipped (written before)$" "$log2" || fail "frame $i was not reported skipped"
    [ "$(stat -c %i "$work/farm/f_00$i.exr") $(stat -c %i "$work/farm/f_00$i.png")" = "${inodes[$k]}" ] \
        || fail "frame $i was written again (its files have new inodes)"
done
diff <(ls -A "$work/whole") <(ls -A "$work/farm") >/dev/null || fail "the farm's files are not the 80 of the single render: $(diff <(ls -A "$work/whole") <(ls -A "$work/farm") | head -5)"
for f in "$work/whole"/*; do
    cmp -s "$f" "$work/farm/${f##*/}" || fail "farm/${f##*/} differs from the single-process render's"
done
echo "farm: resubmission done at $((SECONDS - start_s)) s"

# 3. GNU parallel (its resume is the same --skip-existing as the array's).
cd "$work/par" || exit 1
"$SRC/tools/farm/vksky-parallel.sh" 4 "${SEQ[@]}" 2>"$work/logs/par.err" || fail "vksky-parallel.sh failed: $(tail -3 "$work/logs/par.err")"
[ "$(grep -c '^vksky: 10 frames rendered, 0 skipped' "$work/logs/par.err")" -eq 4 ] || fail "vksky-parallel.sh: not 4 parts of 10 frames"
diff <(ls -A "$work/whole") <(ls -A "$work/par") >/dev/null || fail "vksky-parallel.sh wrote other files than the single render"
for f in "$work/whole"/*; do
    cmp -s "$f" "$work/par/${f##*/}" || fail "par/${f##*/} differs from the single-process render's"
done
cd "$work" || exit 1
echo "farm: GNU parallel done at $((SECONDS - start_s)) s"

# No render reported a validation message (each would also have failed its run).
grep -l 'validation\|Validation' "$work"/logs/* >/dev/null && fail "validation messages: $(grep -h -i validation "$work"/logs/* | head -3)"

# 4. Nothing left running.
cd / || exit 1
kill "$watchdog" 2>/dev/null
wait "$watchdog" 2>/dev/null
stop_all
left=$(leftovers)
[ -z "$left" ] || fail "processes left running: $left"
[ $fails -eq 0 ] && echo "farm: all checks pass in $((SECONDS - start_s)) s"
exit $((fails > 0))
