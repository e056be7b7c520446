#!/usr/bin/env bash
# One frame on a Slurm cluster: a job array with one task per chunk of samples, and a merge job
# that runs after them (afterany) and checks coverage itself.
#
#   tools/slurm/slurm-render.sh SCENE --spp N --chunks K -o FRAME.exr [--gres gpu:1]
#                               [--partition P] [-- more geocold-cl options]
#
# The frame's N samples are cut into chunks of C = ceil(N / K) samples (--chunk-samples C);
# task i renders samples [i*C, min((i+1)*C, N)) into FRAME.exr.parts/part-<i>.exr (a partial
# image, written atomically), on the GPU Slurm binds to it (--gres: NVIDIA's OpenCL honours the
# CUDA_VISIBLE_DEVICES Slurm sets; GEOCOLD_DEVICE overrides the device, default any without a GPU).
# The merge job runs `geocold-cl merge ... --spp N`: the bits of the frame rendered in one
# process, or exit 7 naming the missing sample ranges. (afterany, not afterok: an afterok merge
# never runs once a task has failed, even if the task is requeued and then succeeds.)
#
# Task exit codes: 0 done; 75 retryable (device lost or out of memory, SIGTERM/preemption; the
# task requeues itself, at most GEOCOLD_SLURM_RETRIES times, default 3); 65 fatal (bad scene,
# options or output: retrying cannot help). SIGTERM stops a task at once with nothing
# half-written (an interrupted partial render writes nothing).
#
# Environment: GEOCOLD_CL (the geocold-cl to run; default: beside this script's build, else on
# PATH), SBATCH and SCONTROL (the commands; the tests pass fakes), GEOCOLD_DEVICE.
set -euo pipefail

self="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")"
sbatch_cmd=${SBATCH:-sbatch}
scontrol_cmd=${SCONTROL:-scontrol}

find_cli() {
    if [[ -n "${GEOCOLD_CL:-}" ]]; then echo "$GEOCOLD_CL"; return; fi
    local beside; beside="$(dirname "$self")/../../build/release/geocold-cl"
    if [[ -x "$beside" ]]; then echo "$beside"; return; fi
    command -v geocold-cl || { echo "slurm-render.sh: geocold-cl not found (set GEOCOLD_CL)" >&2; exit 65; }
}

die() { echo "slurm-render.sh: $*" >&2; exit 2; }

# --- an array task: one chunk ---------------------------------------------------------------
if [[ "${1:-}" == "__task" ]]; then
    shift
    scene=$1 spp=$2 chunk=$3 parts=$4; shift 4
    id=${SLURM_ARRAY_TASK_ID:?SLURM_ARRAY_TASK_ID is not set: run through sbatch --array}
    first=$((id * chunk)); end=$((first + chunk)); ((end > spp)) && end=$spp
    # The GPU Slurm bound to the task (it sets CUDA_VISIBLE_DEVICES, which NVIDIA's OpenCL
    # honours, so the task sees that GPU alone), unless GEOCOLD_DEVICE says otherwise.
    device=any
    if [[ -n "${CUDA_VISIBLE_DEVICES:-}${SLURM_JOB_GPUS:-}${SLURM_STEP_GPUS:-}" ]]; then device=gpu; fi
    device=${GEOCOLD_DEVICE:-$device}
    cli=$(find_cli)
    "$cli" "$scene" --quiet --device "$device" --chunk-samples "$chunk" \
        --samples "$first:$end" -o "$parts/part-$id.exr" "$@" &
    child=$!
    trap 'kill -INT "$child" 2>/dev/null || true' TERM INT
    set +e
    wait "$child"; rc=$?
    # wait returns early (>128) when a trapped signal arrives: wait for the child itself.
    while kill -0 "$child" 2>/dev/null; do wait "$child"; rc=$?; done
    set -e
    case $rc in
        0) exit 0 ;;
        4|130|137|143)  # device lost / out of device memory, or stopped by a signal
            restarts=${SLURM_RESTART_COUNT:-0}
            if ((restarts < ${GEOCOLD_SLURM_RETRIES:-3})) && [[ -n "${SLURM_ARRAY_JOB_ID:-}" ]]; then
                echo "slurm-render.sh: task $id: exit $rc, retryable: requeued" >&2
                "$scontrol_cmd" requeue "${SLURM_ARRAY_JOB_ID}_${id}" || true
            fi
            exit 75 ;;
        *) echo "slurm-render.sh: task $id: exit $rc: fatal" >&2; exit 65 ;;
    esac
fi

# --- the merge job ----------------------------------------------------------------------------
if [[ "${1:-}" == "__merge" ]]; then
    shift
    out=$1 spp=$2 parts=$3
    shopt -s nullglob
    files=("$parts"/part-*.exr)
    cli=$(find_cli)
    if ((${#files[@]} == 0)); then echo "slurm-render.sh: no partial images in $parts" >&2; exit 7; fi
    exec "$cli" merge "${files[@]}" --spp "$spp" -o "$out"
fi

# --- submission -------------------------------------------------------------------------------
scene="" spp="" chunks="" out="" gres="" partition=""
extra=()
while (($#)); do
    case $1 in
        --spp) spp=${2:?--spp needs a value}; shift 2 ;;
        --chunks) chunks=${2:?--chunks needs a value}; shift 2 ;;
        -o|--output) out=${2:?-o needs a value}; shift 2 ;;
        --gres) gres=${2:?--gres needs a value}; shift 2 ;;
        --partition) partition=${2:?--partition needs a value}; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        -*) die "unknown option '$1' (geocold-cl options go after --)" ;;
        *) [[ -z "$scene" ]] || die "more than one scene given"; scene=$1; shift ;;
    esac
done
[[ -n "$scene" && -n "$spp" && -n "$chunks" && -n "$out" ]] || die "usage: slurm-render.sh SCENE --spp N --chunks K -o FRAME.exr"
[[ "$spp" =~ ^[1-9][0-9]*$ && "$chunks" =~ ^[1-9][0-9]*$ ]] || die "--spp and --chunks take positive integers"
[[ -f "$scene" ]] || die "no scene file '$scene'"
scene=$(realpath "$scene")
out=$(realpath -m "$out")
chunk=$(((spp + chunks - 1) / chunks))
tasks=$(((spp + chunk - 1) / chunk))
parts="$out.parts"
mkdir -p "$parts"

opts=(--parsable --job-name "geocold:$(basename "$scene")" --output "$parts/slurm-%A_%a.log")
[[ -n "$partition" ]] && opts+=(--partition "$partition")
task_opts=(--array "0-$((tasks - 1))" --requeue)
[[ -n "$gres" ]] && task_opts+=(--gres "$gres")
array_job=$("$sbatch_cmd" "${opts[@]}" "${task_opts[@]}" "$self" __task "$scene" "$spp" "$chunk" "$parts" "${extra[@]}")
array_job=${array_job%%;*}
merge_job=$("$sbatch_cmd" --parsable --job-name "geocold-merge" --output "$parts/slurm-merge-%j.log" \
    --dependency "afterany:$array_job" ${partition:+--partition "$partition"} "$self" __merge "$out" "$spp" "$parts")
merge_job=${merge_job%%;*}
echo "submitted: $tasks tasks of $chunk samples (job $array_job), merge job $merge_job -> $out"
