#!/usr/bin/env bash
# tools/slurm/slurm-render.sh against a real Slurm: munged, slurmctld and slurmd started here
# on localhost as root (no systemd), two fake GPUs through gres.conf (File=/dev/null, /dev/zero),
# everything under a temp folder, stopped and removed at the end. Checks:
#   1. an array of chunks plus the merge job gives the bits of one process;
#   2. kill -9 of a running task's geocold-cl: the task requeues itself and the frame has the
#      same bits;
#   3. a task failing with no retries left: not requeued, the afterany merge runs and fails
#      with exit 7 naming the missing samples;
#   4. kill -9 of slurmd while a task runs, then a restart: the frame has the same bits.
# Exit 77 (ctest: skipped) when not root or Slurm/munge are not installed.
# Usage: real_slurm_test.sh GEOCOLD_CL SOURCE_DIR
set -euo pipefail
cli=$(realpath "$1") src=$(realpath "$2")
if [[ $(id -u) != 0 ]]; then echo "SKIP: needs root to run the Slurm daemons"; exit 77; fi
for b in munged slurmctld slurmd sbatch squeue sacct scontrol; do
    command -v "$b" >/dev/null || { echo "SKIP: $b not installed (tools/install-deps.sh installs Slurm)"; exit 77; }
done

T=$(mktemp -d /var/tmp/gc-slurm.XXXXXX)
chmod 755 "$T"
pids=()
cleanup() {
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    sleep 1
    for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
    # Jobs' processes (slurmstepd and its children) outlive slurmd: end those under our folder.
    for p in $(pgrep -f "$T" || true); do [[ $p != $$ ]] && kill -9 "$p" 2>/dev/null || true; done
    rm -rf "$T"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*" >&2
    for f in "$T"/*.log "$T"/out*/*.parts/*.log; do [[ -f $f ]] && { echo "--- $f"; tail -20 "$f"; }; done >&2
    exit 1
}
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

host=$(hostname -s)
mkdir -p "$T/state" "$T/spool" "$T/munge"
chmod 700 "$T/munge"
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$T/munge/munge.key"
munged --force --key-file "$T/munge/munge.key" --socket "$T/munge/munge.sock" \
    --pid-file "$T/munge/munged.pid" --log-file "$T/munged.log" --seed-file "$T/munge/seed" || fail "munged did not start"
pids+=("$(cat "$T/munge/munged.pid")")

cat > "$T/slurm.conf" <<CONF
ClusterName=gctest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge/munge.sock
CredType=cred/munge
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobRequeue=1
GresTypes=gpu
MinJobAge=600
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host CPUs=$(nproc) Gres=gpu:2 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
CONF
cat > "$T/gres.conf" <<CONF
NodeName=$host Name=gpu File=/dev/null
NodeName=$host Name=gpu File=/dev/zero
CONF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" > "$T/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" > "$T/slurmd.out" 2>&1 &
pids+=($!)
for i in $(seq 60); do
    state=$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)
    [[ $state == idle* ]] && break
    sleep 0.5
done
[[ $state == idle* ]] || fail "the node did not come up (state '$state')"
echo "slurm up: node $host $state"

scene="$src/scenes/cornell-box/CornellBox-Original.obj"
opts=(--res 24x16 --max-depth 4)
export GEOCOLD_CL=$cli GEOCOLD_DEVICE=cpu GEOCOLD_CACHE_DIR=$T/kcache GEOCOLD_CACHE_ALWAYS=1
"$cli" "$scene" --quiet --device cpu --spp 14 --chunk-samples 5 "${opts[@]}" -o "$T/direct.pfm"

# The renderer of the chunk named in $T/hold starts stopped on its task's first run, and its pid
# goes to $T/held.pid: the test then acts on a task that is certainly still running, however
# fast the machine renders the chunk.
cat > "$T/hold.sh" <<WRAP
#!/usr/bin/env bash
hold=\$(cat "$T/hold" 2>/dev/null || true)
if [[ -n \$hold && \${SLURM_RESTART_COUNT:-0} == 0 && " \$* " == *" \$hold "* ]]; then
    "$cli" "\$@" &
    renderer=\$!
    kill -STOP \$renderer
    echo \$renderer > "$T/held.pid.tmp" && mv "$T/held.pid.tmp" "$T/held.pid"
    wait \$renderer
    exit \$?
fi
exec "$cli" "\$@"
WRAP
chmod +x "$T/hold.sh"
# Holds the renderer of chunk $1 in the next submission; prints its pid once it is held.
hold_chunk() { rm -f "$T/held.pid"; echo "$1" > "$T/hold"; }
held_renderer() {
    for i in $(seq 600); do
        [[ -s "$T/held.pid" ]] && { cat "$T/held.pid"; return 0; }
        sleep 0.1
    done
    fail "the renderer of chunk $(cat "$T/hold") did not start within 60 s"
}

# Waits until Slurm has no job left (bounded). Slurm holds a requeued job back for about two
# minutes (reason BeginTime); the test lets it start at once.
wait_idle() {
    for i in $(seq 240); do
        [[ -z $(squeue -h 2>/dev/null) ]] && return 0
        for job in $(squeue -h -t PENDING -o '%i %r' 2>/dev/null | awk '$2 == "BeginTime" {print $1}'); do
            scontrol update JobId="$job" StartTime=now 2>/dev/null || true
        done
        sleep 0.5
    done
    squeue -o "%i %T %r %S %V"; fail "jobs still queued after 120 s"
}

# 1. Array + merge == one process.
mkdir -p "$T/out1"
"$src/tools/slurm/slurm-render.sh" "$scene" --spp 14 --chunks 3 --gres gpu:1 -o "$T/out1/frame.pfm" -- "${opts[@]}"
wait_idle
cmp "$T/out1/frame.pfm" "$T/direct.pfm" || fail "array + merge differs from one process"
echo "ok: array + merge == one process"

# 2. kill -9 of a task's renderer: the task requeues itself; the frame has the same bits.
mkdir -p "$T/out2"
hold_chunk 5:10
submitted=$(GEOCOLD_CL="$T/hold.sh" GEOCOLD_SLURM_RETRIES=3 "$src/tools/slurm/slurm-render.sh" "$scene" \
    --spp 14 --chunks 3 -o "$T/out2/frame.pfm" -- "${opts[@]}")
array=$(sed -n 's/.*(job \([0-9]*\)).*/\1/p' <<< "$submitted")
victim=$(held_renderer)
[[ ! -e "$T/out2/frame.pfm.parts/part-1.exr" ]] || fail "task 1 wrote its partial before it rendered"
kill -9 "$victim"
wait_idle
restarts=$(scontrol show job "${array}_1" | sed -n 's/.*Restarts=\([0-9]*\).*/\1/p')
[[ ${restarts:-0} -ge 1 ]] || fail "task ${array}_1 was not requeued (Restarts=${restarts:-?})"
echo "killed task 1's renderer (pid $victim); the task ran again (Restarts=$restarts)"
cmp "$T/out2/frame.pfm" "$T/direct.pfm" || fail "the frame after a killed and requeued task differs"
echo "ok: kill -9 of a task -> requeued, same bits"
rm -f "$T/hold"

# 3. A task whose device is lost (a wrapper makes task 1's geocold-cl exit 4) with no retries
# left: not requeued; the afterany merge runs and fails with exit 7 naming the samples.
mkdir -p "$T/out3"
cat > "$T/lost-device.sh" <<WRAP
#!/usr/bin/env bash
for a in "\$@"; do [[ \$a == 5:10 ]] && { echo "geocold-cl: error: device lost (simulated)" >&2; exit 4; }; done
exec "$cli" "\$@"
WRAP
chmod +x "$T/lost-device.sh"
GEOCOLD_CL="$T/lost-device.sh" GEOCOLD_SLURM_RETRIES=0 "$src/tools/slurm/slurm-render.sh" "$scene" --spp 14 \
    --chunks 3 -o "$T/out3/frame.pfm" -- "${opts[@]}" >/dev/null
wait_idle
[[ ! -e "$T/out3/frame.pfm" ]] || fail "merge wrote a frame with a chunk missing"
grep -q "missing: 5:10" "$T"/out3/frame.pfm.parts/slurm-merge-*.log || fail "merge did not name 5:10"
echo "ok: a failed task (no retries left) -> merge exit 7 naming 5:10"

# 4. kill -9 of slurmd while a task's renderer is held, slurmd restarted, the renderer let go:
# the frame has the same bits.
big=(--res 160x120 --max-depth 6)
"$cli" "$scene" --quiet --device cpu --spp 24 --chunk-samples 8 "${big[@]}" -o "$T/direct4.pfm"
mkdir -p "$T/out4"
hold_chunk 8:16
GEOCOLD_CL="$T/hold.sh" "$src/tools/slurm/slurm-render.sh" "$scene" --spp 24 --chunks 3 \
    -o "$T/out4/frame.pfm" -- "${big[@]}" >/dev/null
running=$(held_renderer)
slurmd_pid=${pids[2]}
kill -9 "$slurmd_pid"
sleep 2
slurmd -D -f "$SLURM_CONF" -N "$host" >> "$T/slurmd.out" 2>&1 &
pids[2]=$!
kill -CONT "$running"
wait_idle
cmp "$T/out4/frame.pfm" "$T/direct4.pfm" || fail "the frame after slurmd was killed differs"
echo "ok: kill -9 of slurmd while task 1 ran (renderer pid $running) and a restart -> same bits"
echo "all Slurm checks passed"
