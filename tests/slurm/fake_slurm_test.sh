#!/usr/bin/env bash
# tools/slurm/slurm-render.sh against a fake sbatch that runs the tasks on this machine (no
# Slurm daemons): the array's partials merged by the merge job give the bits of the frame
# rendered in one process; a task that never ran makes the merge fail naming its samples; a bad
# scene is a fatal task exit (65); SIGTERM leaves nothing half-written and is retryable (75).
# Usage: fake_slurm_test.sh GEOCOLD_CL SOURCE_DIR
set -euo pipefail
cli=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export GEOCOLD_CL=$cli SBATCH="$src/tests/slurm/fake-sbatch" SCONTROL="true" GEOCOLD_DEVICE=cpu
scene="$src/scenes/cornell-box/CornellBox-Original.obj"
opts=(--res 24x16 --max-depth 4)
fail() { echo "FAIL: $*" >&2; exit 1; }

# 1. Array + merge == one process, bit for bit (14 spp in chunks of 5: 5, 5, 4).
export FAKE_SLURM_DIR="$work/slurm1"; mkdir -p "$FAKE_SLURM_DIR"
"$src/tools/slurm/slurm-render.sh" "$scene" --spp 14 --chunks 3 -o "$work/frame.pfm" -- "${opts[@]}"
cat "$FAKE_SLURM_DIR/exits"
[[ $(grep -c ' 0$' "$FAKE_SLURM_DIR/exits") == 4 ]] || fail "a task or the merge failed: $(cat "$work"/frame.pfm.parts/*.log)"
"$cli" "$scene" --quiet --device cpu --spp 14 --chunk-samples 5 "${opts[@]}" -o "$work/direct.pfm"
cmp "$work/frame.pfm" "$work/direct.pfm" || fail "the merged frame differs from the one-process frame"
echo "ok: array + merge == one process"

# 2. A task that never ran: the merge (afterany) runs, fails with exit 7 naming the samples.
export FAKE_SLURM_DIR="$work/slurm2"; mkdir -p "$FAKE_SLURM_DIR"; touch "$FAKE_SLURM_DIR/skip-1"
"$src/tools/slurm/slurm-render.sh" "$scene" --spp 14 --chunks 3 -o "$work/gap.pfm" -- "${opts[@]}"
grep -q '_merge 7$' "$FAKE_SLURM_DIR/exits" || fail "merge did not exit 7: $(cat "$FAKE_SLURM_DIR/exits")"
grep -q 'missing: 5:10' "$work"/gap.pfm.parts/slurm-merge-*.log || fail "merge did not name 5:10"
[[ ! -e "$work/gap.pfm" ]] || fail "merge wrote an incomplete frame"
echo "ok: a missing chunk fails the merge, naming 5:10"

# 3. A bad scene: every task exits 65 (fatal, no requeue).
export FAKE_SLURM_DIR="$work/slurm3"; mkdir -p "$FAKE_SLURM_DIR"
printf 'v 0 0 0\nf 1 2 3\n' > "$work/bad.obj"
"$src/tools/slurm/slurm-render.sh" "$work/bad.obj" --spp 4 --chunks 2 -o "$work/bad.pfm"
[[ $(grep -c '_[0-9]* 65$' "$FAKE_SLURM_DIR/exits") == 2 ]] || fail "bad scene tasks: $(cat "$FAKE_SLURM_DIR/exits")"
echo "ok: a bad scene is fatal (65)"

# 4. SIGTERM to a running task: exit 75 (retryable) and no partial image, not even a temp file.
mkdir -p "$work/term"
SLURM_ARRAY_TASK_ID=0 "$src/tools/slurm/slurm-render.sh" __task "$scene" 100000 100000 "$work/term" --res 64x64 &
task=$!
sleep 3
kill -TERM "$task"
set +e; wait "$task"; rc=$?; set -e
[[ $rc == 75 ]] || fail "SIGTERM: task exit $rc, not 75"
[[ -z "$(ls -A "$work/term")" ]] || fail "SIGTERM left files: $(ls "$work/term")"
echo "ok: SIGTERM -> 75, nothing written"

# 5. SIGTERM to geocold-cl itself (Slurm signals every process of the task): exit 130, nothing
# written, no temp file.
mkdir -p "$work/term2"
"$cli" "$scene" --quiet --device cpu --samples 0:100000 --chunk-samples 100000 --res 64x64 -o "$work/term2/p.exr" &
pid=$!
sleep 3
kill -TERM "$pid"
set +e; wait "$pid"; rc=$?; set -e
[[ $rc == 130 ]] || fail "SIGTERM to geocold-cl: exit $rc, not 130"
[[ -z "$(ls -A "$work/term2")" ]] || fail "SIGTERM left files: $(ls "$work/term2")"
echo "ok: SIGTERM to geocold-cl -> 130, nothing written"
