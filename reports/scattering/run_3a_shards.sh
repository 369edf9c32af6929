#!/usr/bin/env bash
# DISORT 3a with 6e9 photons (seed 3) as 60 shards of 1e8 photons, run one after the other on
# this machine at low priority (nice 19, or $NICE); a shard already written is skipped, so the script can
# be restarted, and a killed shard leaves no file. Merge when all 60 are there:
#   build/rayint merge reports/scattering/3a-6e9/shard.*.json -o reports/scattering/disort_3a_seed3_6e9.json
# (exit 1 = some benchmark value is not reproduced, as for the single run). On Slurm the same
# run is: scripts/slurm/submit.sh -n 60 -d DIR -r REPORT -- <the rayint arguments below>.
set -u
cd "$(dirname "$0")/../.."
rayint=${RAYINT:-build/rayint}
out=reports/scattering/3a-6e9
n=${N:-60}
mkdir -p "$out"
for i in $(seq 0 $((n - 1))); do
  [ -e "$out/shard.$i.json" ] && continue
  start=$(date +%s)
  nice -n "${NICE:-19}" "$rayint" slab --benchmark cases/scattering/disort_slab.json --problems 3a \
    --photons 6000000000 --seed 3 --json --shard "$i/$n" -o "$out/shard.$i.json" --quiet || exit 1
  echo "$(date -u +%FT%TZ) shard $i/$n done in $(( $(date +%s) - start )) s"
done
echo "all $n shards done"
