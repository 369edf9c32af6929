#!/usr/bin/env bash
# CTest shard_merge_<kind>: a 4-shard run merged with `rayint merge` equals the single run.
#   shard_merge_test.sh RAYINT SOURCE_DIR KIND
#   KIND: stress | slab | slab_benchmark | render | scene | refusals | rerun | bench | scatter | cells
# Reports are compared by tests/compare_reports.py: identical except wall-time fields (keys
# ending in seconds / per_second / _share; bench also its timing-derived fields, see there);
# the stress report and every image byte for byte.
set -euo pipefail
rayint=$1 src=$2 kind=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmp_reports() { /usr/bin/python3 "$src/tests/compare_reports.py" "$@"; }
# refuse_mixed MERGE-ARGS...: `rayint merge` of the given shard files (one of them from another
# run) exits 2 with one line naming a shard of a different run, and writes nothing.
refuse_mixed() {
  rm -f "$work/mixed.out"
  local rc=0; "$rayint" merge "$@" -o "$work/mixed.out" 2>"$work/mixed.err" >/dev/null || rc=$?
  [ "$rc" = 2 ] || { echo "mixed merge: expected exit 2, got $rc"; cat "$work/mixed.err"; exit 1; }
  [ "$(wc -l <"$work/mixed.err")" = 1 ] || { echo "mixed merge: expected one line:"; cat "$work/mixed.err"; exit 1; }
  grep -q "a shard of a different run" "$work/mixed.err" || { echo "mixed merge:"; cat "$work/mixed.err"; exit 1; }
  [ ! -e "$work/mixed.out" ] || { echo "mixed merge wrote output"; exit 1; }
}
shards() {  # shards PREFIX ARGS... : runs shards 0..3 of the run ARGS into PREFIX.I.json
  local prefix=$1; shift
  for i in 0 1 2 3; do "$rayint" "$@" --shard "$i/4" -o "$prefix.$i.json" --quiet; done
}
case $kind in
  stress)
    args=(stress --count 600 --seed 7 --methods exact,riemann:n=8,rk4:n=4 --json)
    # the reports name the worst-case files: both runs write them to $work/worst (the single
    # run's moved to worst1 before the merge writes its own)
    "$rayint" "${args[@]}" --worst-dir "$work/worst" -o "$work/one.json" -q
    mv "$work/worst" "$work/worst1"
    shards "$work/s" "${args[@]}" --worst-dir "$work/worst"
    [ ! -e "$work/worst" ] || { echo "a shard wrote worst cases"; exit 1; }
    "$rayint" merge "$work"/s.{3,1,0,2}.json -o "$work/merged.json"
    cmp "$work/one.json" "$work/merged.json"
    for f in "$work"/worst1/*; do cmp "$f" "$work/worst/$(basename "$f")"; done
    [ "$(ls "$work/worst1" | wc -l)" = "$(ls "$work/worst" | wc -l)" ]
    echo "stress: 4-shard merge == one run, byte for byte ($(wc -c <"$work/one.json") bytes, $(ls "$work/worst1" | wc -l) worst cases)"
    ;;
  slab)
    args=(slab --tau 1 --albedo 0.9 --phase hg:0.7 --mu-up 0.1,0.5 --mu-down 0.1,1 --method monte_carlo
          --photons 200000 --seed 3)
    "$rayint" "${args[@]}" -o "$work/one.json" --quiet
    shards "$work/s" "${args[@]}"
    "$rayint" merge "$work"/s.{0,1,2,3}.json -o "$work/merged.json"
    cmp_reports "$work/one.json" "$work/merged.json"
    "$rayint" "${args[@]}" --mc-analog -o "$work/one_analog.json" --quiet
    shards "$work/a" "${args[@]}" --mc-analog
    "$rayint" merge "$work"/a.{2,0,3,1}.json -o "$work/merged_analog.json"
    cmp_reports "$work/one_analog.json" "$work/merged_analog.json"
    echo "slab: 4-shard merge == one run (split and analog estimators), except wall-time fields"
    ;;
  slab_benchmark)
    args=(slab --benchmark "$src/cases/scattering/disort_slab.json" --problems 3a,1b --photons 100000 --seed 5 --json)
    rc1=0; "$rayint" "${args[@]}" -o "$work/one.json" --quiet || rc1=$?
    shards "$work/s" "${args[@]}"
    rc2=0; "$rayint" merge "$work"/s.{0,1,2,3}.json -o "$work/merged.json" || rc2=$?
    [ "$rc1" = "$rc2" ] || { echo "exit codes differ: $rc1 vs $rc2"; exit 1; }
    cmp_reports "$work/one.json" "$work/merged.json"
    echo "slab --benchmark: 4-shard merge == one run (exit $rc1 both), except wall-time fields"
    ;;
  render)
    # the stats name the image's heat map: both runs write the same paths (the single run's
    # outputs moved aside before the merge writes its own)
    args=(render "$src/cases/mesh-ball-radial.json" --compare riemann:n=4 --stats "$work/stats.json")
    "$rayint" "${args[@]}" -o "$work/img.png" --quiet
    for f in img.png img.error.png stats.json; do mv "$work/$f" "$work/one.$f"; done
    shards "$work/s" "${args[@]}"
    [ ! -e "$work/stats.json" ] || { echo "a shard wrote the stats"; exit 1; }
    "$rayint" merge "$work"/s.{1,3,2,0}.json -o "$work/img.png"
    cmp "$work/one.img.png" "$work/img.png"
    cmp "$work/one.img.error.png" "$work/img.error.png"
    cmp_reports "$work/one.stats.json" "$work/stats.json"
    echo "render: 4-shard merge == one run (image and heat map byte for byte; stats except wall-time fields)"
    ;;
  scene)
    # A scene with a camera (rows) and one of explicit rays (rays): the merged image and stats
    # equal the single run's (image byte for byte as .npy float64; stats except wall-time fields).
    cp "$src/cases/scenes/ground.png" "$work/"  # the scene's background image, beside it
    /usr/bin/python3 - "$src/cases/scenes/cloud-single-scattering-shadows.json" "$work" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["camera"]["width"], s["camera"]["height"] = 13, 11
json.dump(s, open(sys.argv[2] + "/cam.json", "w"))
del s["camera"]
s["rays"] = [{"origin": [0.1 * i - 0.3, 0.15, 4.2], "direction": [0, 0, -1]} for i in range(7)]
json.dump(s, open(sys.argv[2] + "/rays.json", "w"))
PY
    for sc in cam rays; do
      args=(render "$work/$sc.json" --stats "$work/stats.json")
      "$rayint" "${args[@]}" -o "$work/img.npy" --quiet
      for f in img.npy stats.json; do mv "$work/$f" "$work/one.$f"; done
      shards "$work/s" "${args[@]}"
      [ ! -e "$work/stats.json" ] || { echo "a shard wrote the stats"; exit 1; }
      "$rayint" merge "$work"/s.{2,0,3,1}.json -o "$work/img.npy"
      cmp "$work/one.img.npy" "$work/img.npy"
      cmp_reports "$work/one.stats.json" "$work/stats.json"
      rm -f "$work"/s.*.json "$work"/one.* "$work/img.npy" "$work/stats.json"
    done
    echo "scene: 4-shard merge == one run for a camera scene (rows) and a scene of 7 explicit rays (image byte for byte, stats except wall-time fields)"
    ;;
  refusals)
    args=(slab --tau 1 --albedo 0.9 --phase isotropic --mu-up 0.5 --method monte_carlo --photons 50000)
    shards "$work/s" "${args[@]}" --seed 1
    "$rayint" "${args[@]}" --seed 2 --shard 1/4 -o "$work/other.1.json" --quiet
    expect_fail() {  # expect_fail PATTERN CMD...: exit 2, one line on stderr matching PATTERN, no output
      local pattern=$1; shift
      rm -f "$work/out.json"
      local rc=0; "$@" 2>"$work/err" >/dev/null || rc=$?
      [ "$rc" = 2 ] || { echo "expected exit 2, got $rc: $*"; cat "$work/err"; exit 1; }
      [ "$(wc -l <"$work/err")" = 1 ] || { echo "expected one line:"; cat "$work/err"; exit 1; }
      grep -q -- "$pattern" "$work/err" || { echo "expected '$pattern' in:"; cat "$work/err"; exit 1; }
      [ ! -e "$work/out.json" ] || { echo "partial output written"; exit 1; }
    }
    expect_fail "missing shard 2/4" "$rayint" merge "$work"/s.{0,1,3}.json -o "$work/out.json"
    expect_fail "duplicate of shard 1/4" "$rayint" merge "$work"/s.{0,1,1,2,3}.json -o "$work/out.json"
    expect_fail "different run" "$rayint" merge "$work"/s.{0,2,3}.json "$work/other.1.json" -o "$work/out.json"
    expect_fail "not a shard file" "$rayint" merge "$src/cases/scattering/disort_slab.json" -o "$work/out.json"
    # A Monte Carlo shard with a block node removed (its photons left out) is refused.
    /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); n=j['data']['monte_carlo'][0]['nodes']; assert len(n) > 1, n; n.pop(); json.dump(j,open(sys.argv[2],'w'))" \
      "$work/s.1.json" "$work/gap.s.1.json"
    expect_fail "data.monte_carlo\[0\].nodes: shard 1/4 of 13 must cover \[3, 6), but covers \[3, 4)" \
      "$rayint" merge "$work"/s.0.json "$work/gap.s.1.json" "$work"/s.{2,3}.json -o "$work/out.json"
    # a shard without -o is refused before the work (a run of hours here would hit the timeout)
    expect_fail "needs -o FILE" timeout 60 "$rayint" slab --tau 1 --albedo 0.9 --phase isotropic --mu-up 0.5 \
      --method monte_carlo --photons 10000000000 --seed 1 --shard 0/4
    expect_fail "needs -o FILE" timeout 60 "$rayint" stress --count 100000000 --seed 1 --shard 0/4
    # The files a case names are inputs too: a render of a TetGen mesh case (case JSON -> .ele,
    # which names its .node) refuses to merge once the .node file has changed after the shards ran.
    cp "$src/tests/fixtures/meshes/cube.1.ele" "$src/tests/fixtures/meshes/cube.1.node" "$work/"
    cat >"$work/tetgen-cam.json" <<'JSON'
{"name": "tetgen-cube-camera", "transfer_function": {"density": [[-0.5, 0.2], [0.4, 1.6], [1.5, 0.4]], "color": [[-0.5, 0.1], [1.5, 0.9]]},
 "mesh_file": "cube.1.ele",
 "camera": {"position": [2.5, 2, 3.5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40, "width": 8, "height": 8}}
JSON
    for i in 0 1; do "$rayint" render "$work/tetgen-cam.json" --shard $i/2 -o "$work/r.$i.json" --quiet; done
    # the same run with --fit (the camera it used is a result line, printed once the output is written)
    for i in 0 1; do "$rayint" render "$work/tetgen-cam.json" --fit --shard $i/2 -o "$work/f.$i.json" --quiet 2>/dev/null; done
    "$rayint" merge "$work"/r.{0,1}.json -o "$work/r.png" 2>/dev/null  # unchanged inputs: merges
    # A shard whose rows were edited (row 4 left out: shard 1/2 claims rows [5, 8)) is refused:
    # every shard must hold exactly its band of the image.
    /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); d=j['data']; d['row_begin']=5; d['image']=d['image'][3*d['width']:]; json.dump(j,open(sys.argv[2],'w'))" \
      "$work/r.1.json" "$work/gap.1.json"
    expect_fail "data.row_begin: shard 1/2 of 8 must cover \[4, 8), but covers \[5, 8)" \
      "$rayint" merge "$work"/r.0.json "$work/gap.1.json" -o "$work/out.png"
    sed -i 's/^   1    -0.146254 /   1    -0.146255 /' "$work/cube.1.node"
    rm -f "$work/out.png"
    expect_fail "input files changed" "$rayint" merge "$work"/r.{0,1}.json -o "$work/out.png"
    # --fit: the merge's error is its only line (the fit's camera line was printed before it)
    expect_fail "input files changed" "$rayint" merge "$work"/f.{0,1}.json -o "$work/out.png"
    [ ! -e "$work/out.png" ] || { echo "a refused merge wrote its image"; exit 1; }
    "$rayint" merge --allow-partial "$work"/s.{0,1,3}.json -o "$work/partial.json" 2>"$work/err"
    grep -q "partial: 3 of 4 shards (missing 2/4)" "$work/err"
    /usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); n=r['monte_carlo']['photons']; assert 0 < n < 50000, n; print('partial merge covers', n, 'photons')" "$work/partial.json"
    echo "refusals: missing, duplicate, different run, not a shard, shard without -o, a row or a block left out, a changed mesh file: one line, exit 2, no output"
    ;;
  rerun)
    # A shard killed mid-run leaves no file; running it again reproduces it (the shard data are
    # the same bit for bit except its wall-time fields).
    args=(slab --tau 2 --albedo 0.95 --phase hg:0.5 --mu-up 0.5 --mu-down 0.1 --method monte_carlo --photons 3000000 --seed 9)
    "$rayint" "${args[@]}" --shard 2/4 -o "$work/first.json" --quiet
    "$rayint" "${args[@]}" --shard 2/4 -o "$work/killed.json" --quiet &
    pid=$!
    sleep 0.3
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    if [ -e "$work/killed.json" ]; then echo "note: the shard finished before the kill"; else echo "killed shard left no file"; fi
    ls "$work" | grep -q 'killed.json.tmp' && { echo "temporary file left"; exit 1; }
    "$rayint" "${args[@]}" --shard 2/4 -o "$work/killed.json" --quiet
    cmp_reports "$work/first.json" "$work/killed.json"
    echo "rerun: a re-run shard equals the first run of it (except wall-time fields)"
    ;;
  bench)
    # Cases with every kind of outcome: a method failing on a case (particle on varying colour),
    # underflow (thick-absorber-background), many segments; 4 shards split the rays unevenly
    # and across case boundaries. Timing: 1 batch of >= 10 us per ray (fast; still measured).
    cases=("$src"/cases/{paper-figure-2,constant-density-varying-color,many-segments-background,thick-absorber-background,narrow-pulse}.json)
    args=(bench "${cases[@]}" --methods paper,particle,eq6,psi_table --batches 1 --batch-seconds 1e-5)
    "$rayint" "${args[@]}" -o "$work/one.json" --quiet >/dev/null
    shards "$work/s" "${args[@]}"
    "$rayint" merge "$work"/s.{2,0,3,1}.json -o "$work/merged.json" >"$work/table.txt"
    grep -q "wrote $work/merged.json" "$work/table.txt"
    # Timing fields: every key ending in seconds or seconds_per_ray (times per ray are each measured once, in
    # whichever run owns the ray), cost_vs_exact (a ratio of two times), the run's start time and
    # load averages, and the target table (each choice is "least seconds_per_ray"): the target
    # table of the merged report is checked against its own settings instead (compare_reports.py
    # --bench-targets recomputes it from the documented rule).
    cmp_reports "$work/one.json" "$work/merged.json" --ignore seconds_per_ray --ignore median_seconds_per_ray \
      --ignore exact_seconds_per_ray --ignore cost_vs_exact --ignore started_at \
      --ignore load_average_start --ignore load_average_end --ignore targets
    cmp_reports --bench-targets "$work/merged.json"
    cmp_reports --bench-targets "$work/one.json"
    /usr/bin/python3 - "$work/merged.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
m = {x["method"]: x for x in r["methods"]}
p = m["particle"]["settings"][0]
assert p["failed_rays"] > 0 and "failure" in p, p  # a failing setting went through the merge
assert all(s["seconds_per_ray"] > 0 for x in r["methods"] for s in x["settings"] if s["channels"])
print("bench: settings", sum(len(x["settings"]) for x in r["methods"]), "rays", r["rays"],
      "particle failed on", p["failed_rays"], "rays")
PY
    # --allow-partial without shard 2/4 (rays floor(18*2/4) = 9 .. floor(18*3/4) = 13 of 18): the
    # other 14 rays, 42 channels of exact
    "$rayint" merge --allow-partial "$work"/s.{0,1,3}.json -o "$work/partial.json" 2>"$work/err" >/dev/null
    grep -q "partial: 3 of 4 shards (missing 2/4)" "$work/err"
    /usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); e=r['methods'][0]['settings'][0]; assert r['methods'][0]['method']=='exact' and e['channels']==42, e['channels']; print('partial bench merge: exact on', e['channels'], 'channels')" "$work/partial.json"
    "$rayint" "${args[@]:0:$((${#args[@]}-2))}" --batch-seconds 2e-5 --shard 1/4 -o "$work/other.1.json" --quiet
    refuse_mixed "$work"/s.{0,2,3}.json "$work/other.1.json"
    echo "bench: 4-shard merge == one run on every error figure, count and worst case; merge refuses a shard of another run"
    ;;
  scatter)
    args=(scatter "$src/cases/scenes/cloud-multiple-scattering.json" --width 14 --height 10 --spp 6
          --points 12 --grids 4,6 --bins 1,2 --zonal-grids 3,4)
    "$rayint" "${args[@]}" -o "$work/one.json" --images "$work/img" --quiet
    mv "$work/img" "$work/img1"
    shards "$work/s" "${args[@]}" --images "$work/img"
    [ ! -e "$work/img" ] || { echo "a shard wrote images"; exit 1; }
    "$rayint" merge "$work"/s.{3,0,2,1}.json -o "$work/merged.json"
    cmp_reports "$work/one.json" "$work/merged.json"
    n=0; for f in "$work"/img1/*.png; do cmp "$f" "$work/img/$(basename "$f")"; n=$((n+1)); done
    [ "$n" = "$(ls "$work/img" | wc -l)" ] && [ "$n" -gt 2 ]
    "$rayint" "${args[@]}" --seed 6 --shard 2/4 -o "$work/other.2.json" --quiet  # the default seed is 1
    refuse_mixed "$work"/s.{0,1,3}.json "$work/other.2.json"
    echo "scatter: 4-shard merge == one run (report except wall-time fields, $n PNG images byte for byte); merge refuses a shard of another run"
    ;;
  cells)
    # 9 cells per type and 7 rays per voxel grid: the 4 shards get unequal parts
    args=(cells --count 9 --seed 3 --rays 2 --levels 1,2,4 --voxel-sizes 4,6 --voxel-rays 7)
    "$rayint" "${args[@]}" -o "$work/one.json" --quiet >/dev/null
    shards "$work/s" "${args[@]}"
    "$rayint" merge "$work"/s.{1,3,0,2}.json -o "$work/merged.json" >/dev/null
    # times per ray (CPU microseconds, milliseconds) are measured per sample, in whichever run
    # owns the sample: timing fields, like the keys ending in seconds
    cmp_reports "$work/one.json" "$work/merged.json" --ignore decompose_us_per_ray --ignore exact_us_per_ray \
      --ignore us_per_ray --ignore ms_per_ray --ignore reference_ms_per_ray
    "$rayint" cells --count 9 --seed 4 --rays 2 --levels 1,2,4 --voxel-sizes 4,6 --voxel-rays 7 \
      --shard 0/4 -o "$work/other.0.json" --quiet
    refuse_mixed "$work/other.0.json" "$work"/s.{1,2,3}.json
    echo "cells: 4-shard merge == one run (except wall/CPU-time fields); merge refuses a shard of another run"
    ;;
  *) echo "unknown kind $kind"; exit 2 ;;
esac
