#!/usr/bin/env bash
# Submits a rayint run as N shards (a Slurm array job) and the merge job that depends on them.
#   scripts/slurm/submit.sh -n N -d OUT_DIR -r REPORT [-w] [-- SBATCH_OPTIONS... --] -- RAYINT_ARGS...
# e.g. scripts/slurm/submit.sh -n 16 -d runs/3a -r reports/3a.json -- \
#        slab --benchmark cases/scattering/disort_slab.json --problems 3a --photons 6000000000 --seed 3 --json
# -w waits for the merge job and exits with its exit code (sbatch --wait).
# Environment: RAYINT (the rayint executable; default: rayint on PATH), SBATCH_EXTRA (more sbatch
# options for both jobs, e.g. "--partition=short --time=02:00:00 --cpus-per-task=4").
# Prints the array job id and the merge job id.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
n="" out="" report="" wait=0
while [ $# -gt 0 ]; do
  case $1 in
    -n) n=$2; shift 2 ;;
    -d) out=$2; shift 2 ;;
    -r) report=$2; shift 2 ;;
    -w) wait=1; shift ;;
    --) shift; break ;;
    *) echo "submit.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [ -z "$n" ] || [ -z "$out" ] || [ -z "$report" ] || [ $# -eq 0 ]; then
  echo "usage: submit.sh -n N -d OUT_DIR -r REPORT [-w] -- RAYINT_ARGS..." >&2
  exit 2
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
case $report in /*) ;; *) report=$PWD/$report ;; esac
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_EXTRA:-} --chdir="$PWD" --output="$out/slurm-%A_%a.out" \
        --array=0-$((n - 1)) "$here/rayint-shard.sbatch" "$n" "$out" "$@")
array=${array%%;*}
waitopt=()
[ "$wait" = 1 ] && waitopt=(--wait)
echo "array job $array: $n shards of: rayint $*"
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_EXTRA:-} --chdir="$PWD" --output="$out/slurm-merge-%j.out" \
        --dependency=afterok:"$array" --kill-on-invalid-dep=yes "${waitopt[@]}" \
        "$here/rayint-merge.sbatch" "$out" "$report")
echo "merge job ${merge%%;*}: $report"
