#!/usr/bin/env bash
# CTest reliability_limits (label reliability): the CLI against the resource limits, the numbers
# that used to miss silently and the merges of issue 30. Every refusal must be exit 2, exactly one
# line on stderr naming the option or field, and no output file.
#   reliability_limits_test.sh RAYINT SOURCE_DIR
set -uo pipefail
rayint=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# refuse NAME PATTERN CMD...: exit 2, one line matching PATTERN, no out.* file written.
refuse() {
  local name=$1 pattern=$2; shift 2
  rm -f out.* err
  local rc=0; "$@" >/dev/null 2>err || rc=$?
  if [ "$rc" != 2 ]; then fail "$name: exit $rc, expected 2: $(head -c 300 err)"; return; fi
  if [ "$(wc -l <err)" != 1 ]; then fail "$name: $(wc -l <err) lines on stderr:"; cat err; return; fi
  if ! grep -q -- "$pattern" err; then fail "$name: no '$pattern' in: $(cat err)"; return; fi
  if ls out.* >/dev/null 2>&1; then fail "$name: wrote $(ls out.*)"; return; fi
  echo "ok $name: $(cat err)"
}
mkdir meshes
cp "$src/cases/meshes/ball.vtk" meshes/
case=$src/cases/mesh-ball-radial.json
/usr/bin/python3 - "$case" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["mesh_file"] = "meshes/ball.vtk"
c["camera"]["width"] = c["camera"]["height"] = 16
json.dump(c, open("small.json", "w"))
c["camera"]["position"] = [0, 0, 3e16]
json.dump(c, open("far.json", "w"))
PY

# Numbers: NaN and infinities for double options (a central check in cli/options.hpp).
refuse exposure_nan "--exposure" "$rayint" render small.json -o out.png --exposure nan -q
refuse exposure_inf "must be a finite number" "$rayint" render small.json -o out.png --exposure inf -q
refuse exposure_overflow "must be a finite number" "$rayint" render small.json -o out.png --exposure 1e400 -q
refuse progress_every_nan "--progress-every" "$rayint" eval "$src/cases/thin-pieces.json" --progress-every nan -o out.json
refuse slab_tau_nan "--tau" "$rayint" slab --tau nan --albedo 0.5 --phase isotropic --source beam --mu0 1 --mu-up 1 --mu-down 1 -q -o out.txt
# Far origin: an error naming the camera field, not the background.
refuse far_origin "far.json: camera.position" "$rayint" render far.json -o out.png -q

# Resource limits, each before the memory is taken (and each overridable).
refuse photons "--photons: 1e+15 photons is above the limit" "$rayint" slab --tau 1 --albedo 0.5 --phase isotropic \
  --source beam --mu0 1 --mu-up 1 --mu-down 1 --method monte_carlo --photons 1e15 -q -o out.txt
refuse stress_count "--count: 1e+09 samples" "$rayint" stress --count 1e9 -q -o out.json
refuse stress_count_env "RAYINT_MAX_STRESS_COUNT" env RAYINT_MAX_STRESS_COUNT=10 "$rayint" stress --count 11 -q -o out.json
refuse bad_env "RAYINT_MAX_STRESS_COUNT: must be a whole number" env RAYINT_MAX_STRESS_COUNT=lots "$rayint" stress --count 11 -q -o out.json
refuse camera_bytes "small.json: camera: 16 x 16 pixels" env RAYINT_MAX_IMAGE_BYTES=1000 "$rayint" render small.json -o out.png -q
refuse shard_arg "--shard 0/200000: 2e+05 shards" "$rayint" stress --count 10 --shard 0/200000 -o out.json -q
# Range messages in short form (CLI11's own printed 309 digits for --exposure -1).
refuse exposure_negative "--exposure: must be > 0, got -1" "$rayint" render small.json -o out.png --exposure -1 -q
# Integer options say what would do (CLI11's own: "Could not convert: --count = 2.5").
refuse count_fraction "--count: must be a whole number, got 2.5" "$rayint" stress --count 2.5 -q -o out.json
cat > gate.json <<'JSON'
{"stress": {"count": 1000000000000, "seed": 1}}
JSON
refuse gate_stress_count "stress.count" "$rayint" gate --config gate.json -o out.json -q
# A PNG decompression bomb: a 3000 x 3000 PNG of zeros is ~30 kB; refused before decoding.
/usr/bin/python3 - <<'PY'
import struct, zlib
w = h = 3000
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
raw = zlib.compress(b"".join(b"\0" + b"\0" * (3 * w) for _ in range(h)), 9)
open("bomb.png", "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                              + chunk(b"IDAT", raw) + chunk(b"IEND", b""))
PY
refuse png_bomb "bomb.png: (image): 3000 x 3000 pixels" env RAYINT_MAX_IMAGE_BYTES=100000000 \
  "$rayint" check small.json --candidate-image bomb.png -o out.json

# Shards: a hand-edited count, and shards made against two different meshes.
"$rayint" stress --count 20 --seed 3 --shard 0/2 -o s0.json -q
"$rayint" stress --count 20 --seed 3 --shard 1/2 -o s1.json -q
/usr/bin/python3 -c "
import json; j = json.load(open('s1.json')); j['shard']['count'] = 10**18; j['shard']['index'] = 1
json.dump(j, open('s1big.json', 'w'))"
refuse shard_file_count "s1big.json: shard.count: 1e+18 shards" "$rayint" merge s0.json s1big.json -o out.json
"$rayint" render small.json --shard 0/2 -o r0.json -q
"$rayint" generate-mesh ball --n 3 -o meshes/ball.vtk >/dev/null 2>&1 || fail "generate-mesh"
"$rayint" render small.json --shard 1/2 -o r1.json -q
refuse shards_two_meshes "a shard of a different run" "$rayint" merge r0.json r1.json -o out.png

# A full disk (ulimit -f, SIGXFSZ ignored so the write fails with EFBIG): one line, exit 2, the
# previous file intact.
# A 16 x 16 .npy is 6 kB, above the 1 kB file size limit.
echo previous >out.keep.npy
( trap '' XFSZ; ulimit -f 1; "$rayint" render small.json -o out.keep.npy -q 2>err; echo $? >rc )
[ "$(cat rc)" = 2 ] || fail "full disk: exit $(cat rc)"
[ "$(wc -l <err)" = 1 ] || { fail "full disk: not one line"; cat err; }
[ "$(cat out.keep.npy)" = previous ] || fail "full disk: the previous file changed"
ls out.keep.npy.tmp* >/dev/null 2>&1 && fail "full disk: a temporary left behind"
echo "ok full_disk: $(cat err)"
# A memory limit of the machine (ulimit -v): one line, exit 2, never a crash.
/usr/bin/python3 -c "
import json; c = json.load(open('small.json')); c['camera']['width'] = c['camera']['height'] = 8192
json.dump(c, open('big.json', 'w'))"
# Under ASan (RAYINT_SANITIZED=1, set by CMake for the sanitizer build) no process starts under
# ulimit -v: ASan reserves terabytes of shadow address space first. The case is skipped there, by
# name; every ordinary build runs it.
if [ -n "${RAYINT_SANITIZED:-}" ]; then
  echo "skipped ulimit_v: an ASan build cannot start under ulimit -v"
else
  ( ulimit -v 600000; "$rayint" render big.json -o out.png -q 2>err; echo $? >rc )
  [ "$(cat rc)" = 2 ] || fail "ulimit -v: exit $(cat rc)"
  [ "$(wc -l <err)" = 1 ] || { fail "ulimit -v: not one line"; cat err; }
  echo "ok ulimit_v: $(cat err)"
fi
# The address-space limit of the commands below (none under ASan, see above).
vlimit() { if [ -n "${RAYINT_SANITIZED:-}" ]; then echo "ulimit -v unlimited"; else echo "ulimit -v $1"; fi; }

# Shard coverage: every kind's merge proves its shards cover the work exactly once. A shard
# whose data were edited to leave items out (a gap) or hold another shard's (an overlap) is one
# line naming the file and field. Scenes shard like mesh renders (rows; explicit rays: rays).
/usr/bin/python3 - "$src/cases/scenes/cloud-emission.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["camera"]["width"], s["camera"]["height"] = 9, 8
json.dump(s, open("scene.json", "w"))
PY
"$rayint" render scene.json --shard 0/2 -o sc0.json -q || fail "scene shard 0/2"
"$rayint" render scene.json --shard 1/2 -o sc1.json -q || fail "scene shard 1/2"
"$rayint" merge sc0.json sc1.json -o merged.npy 2>err || fail "scene merge: $(cat err)"
"$rayint" render scene.json -o one.npy -q || fail "scene render"
cmp -s one.npy merged.npy && echo "ok scene_shards: 2-shard merge == one run" || fail "scene merge differs from one run"
/usr/bin/python3 -c "
import json; j = json.load(open('sc1.json')); d = j['data']; w = d['width']
d['line_begin'] += 1; d['pixels'] = d['pixels'][3 * w:]; d['line_sums'] = d['line_sums'][3 * (d['terms'] + 1):]
json.dump(j, open('sc1gap.json', 'w'))"
refuse scene_row_gap "sc1gap.json: data.line_begin: shard 1/2 of 8 must cover \[4, 8), but covers \[5, 8)" \
  "$rayint" merge sc0.json sc1gap.json -o out.npy
refuse scene_shard_errors "--errors: not with --shard" "$rayint" render scene.json --errors 2 --shard 0/2 -o out.json -q
/usr/bin/python3 -c "
import json; j = json.load(open('s1.json')); j['data']['regimes'][0]['samples'] += 1
json.dump(j, open('s1over.json', 'w'))"
refuse stress_overlap "s1over.json: data.regimes\[0\].samples: shard 1/2 of this run covers" \
  "$rayint" merge s0.json s1over.json -o out.json
"$rayint" cells --count 3 --voxel-rays 5 --shard 0/2 -o c0.json -q || fail "cells shard 0/2"
"$rayint" cells --count 3 --voxel-rays 5 --shard 1/2 -o c1.json -q || fail "cells shard 1/2"
/usr/bin/python3 -c "
import json; j = json.load(open('c1.json')); j['data']['voxels'][0].pop()
json.dump(j, open('c1gap.json', 'w'))"
refuse cells_gap "c1gap.json: data.voxels\[0\] (rays): shard 1/2 of this run covers 3, but its data hold 2" \
  "$rayint" merge c0.json c1gap.json -o out.json
bench=("$src/cases/paper-figure-2.json" "$src/cases/narrow-pulse.json" --methods paper --batches 1 --batch-seconds 1e-5)
"$rayint" bench "${bench[@]}" --shard 0/2 -o b0.json -q >/dev/null || fail "bench shard 0/2"
"$rayint" bench "${bench[@]}" --shard 1/2 -o b1.json -q >/dev/null || fail "bench shard 1/2"
/usr/bin/python3 -c "
import json; j = json.load(open('b1.json'))
for axis in j['data']['methods']:
    for setting in axis:
        for c in setting['cases']:
            if c['covered'] > 1: c['first_ray'] -= 1; break
json.dump(j, open('b1over.json', 'w'))"
refuse bench_overlap "b1over.json: data.methods\[0\]\[0\].cases\[[0-9]\].first_ray: shard 1/2 must cover" \
  "$rayint" merge b0.json b1over.json -o out.json

# A candidate's size is read from its header and compared with the camera before any pixel is
# read: a 16384 x 16384 PNG (only its first rows' data present) and a .npy header of that shape
# (no data) are refused with the size message -- decoding would fail otherwise ("cannot decode",
# "bytes of data") or take 6.75 GiB.
/usr/bin/python3 - <<'PY'
import struct, zlib
w = h = 16384
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
rows = zlib.compress(b"".join(b"\0" + b"\0" * (3 * w) for _ in range(4)))[:-4]  # a stream cut short
open("huge.png", "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                              + chunk(b"IDAT", rows) + chunk(b"IEND", b""))
header = "{'descr': '<f8', 'fortran_order': False, 'shape': (16384, 16384, 3), }"
header += " " * (63 - (len(header) + 10) % 64) + "\n"
open("huge.npy", "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
PY
refuse png_candidate_header "huge.png: (image): 16384 x 16384 pixels, the camera of small.json has 16 x 16" \
  bash -c "$(vlimit 2000000); exec \"$rayint\" check small.json --candidate-image huge.png -o out.json"
refuse npy_candidate_header "huge.npy: (image): 16384 x 16384 pixels, the camera of small.json has 16 x 16" \
  "$rayint" check small.json --candidate-image huge.npy -o out.json

# Far ray origins in a mesh case (eval): an error naming the case and the ray, not a miss.
/usr/bin/python3 - <<'PY'
import json
c = json.load(open("small.json"))
del c["camera"]
c["rays"] = [{"origin": [0, 0, 3], "direction": [0, 0, -1]}, {"origin": [0, 0, 4e16], "direction": [0, 0, -1]}]
json.dump(c, open("far_rays.json", "w"))
PY
refuse eval_far_origin "far_rays.json: rays\[1\].origin: 4e+16 from the mesh" "$rayint" eval far_rays.json -o out.json -q

# Numbers: a domain per option (docs/limits.md, "Domains"); a sample of them, out of domain.
S=$src/cases/scenes/cloud-multiple-scattering.json
refuse scatter_exposure "--exposure: must be > 0, got -1" "$rayint" scatter "$S" --exposure -1 -o out.json -q
refuse scatter_width "--width/--height: must be in \[1, 4096\]" "$rayint" scatter "$S" --width 0 -o out.json -q
refuse slab_albedo "albedo must be in \[0, 1\]" "$rayint" slab --tau 1 --albedo 2 --mu-up 0.5 -o out.json -q
refuse slab_streams "--streams: must be in \[2, 1024\]" "$rayint" slab --tau 1 --albedo 0.5 --mu-up 0.5 --streams 1 -o out.json -q
refuse cells_count "--count" "$rayint" cells --count 0 -o out.json -q
refuse cells_ode_rtol "--ode-rtol: must be in \[1e-15, 0.5\], got 1e-20" "$rayint" cells --ode-rtol 1e-20 -o out.json -q
refuse check_alpha "--alpha: must be in \[1e-12, 0.5\], got 0.9" "$rayint" check small.json --candidate-image huge.npy --alpha 0.9 -o out.json

# converge: every numeric option's domain (docs/limits.md), checked before the scene is read.
conv() { "$rayint" converge "$src/docs/examples/grid-scene.json" --methods riemann -o out.json -q "$@"; }
refuse converge_steps_nan "--steps: must be a finite number, got nan" conv --steps 0.1,nan
refuse converge_steps_inf "--steps: must be a finite number, got 1e400" conv --steps 0.1,1e400
refuse converge_steps_zero "--steps: 0 is not a distance > 0" conv --steps 0.1,0
refuse converge_steps_negative "--steps: -1 is not a distance > 0" conv --steps 0.1,-1
refuse converge_steps_one "--steps: give at least 2 sample distances" conv --steps 0.1
refuse converge_expect_order_nan "--expect-order: must be a finite number, got nan" conv --steps 0.2,0.1 --expect-order nan
refuse converge_expect_order_negative "--expect-order: must be in (0, 100\], got -1" conv --steps 0.2,0.1 --expect-order -1
refuse converge_expect_order_zero "--expect-order: must be in (0, 100\], got 0" conv --steps 0.2,0.1 --expect-order 0
refuse converge_expect_order_huge "--expect-order: must be in (0, 100\], got 1e+09" conv --steps 0.2,0.1 --expect-order 1e9
refuse converge_order_tolerance_nan "--order-tolerance: must be >= 0, got nan" conv --steps 0.2,0.1 --order-tolerance nan
refuse converge_order_tolerance_negative "--order-tolerance: must be >= 0, got -0.1" conv --steps 0.2,0.1 --order-tolerance -0.1
refuse converge_order_tolerance_order "--order-tolerance: 1 must be below --expect-order 1" \
  conv --steps 0.2,0.1 --expect-order 1 --order-tolerance 1
refuse converge_invariance_nan "--invariance-tolerance: must be a finite number, got nan" conv --steps 0.2,0.1 --invariance-tolerance nan
refuse converge_invariance_negative "--invariance-tolerance: must be in \[0, 1\] (a fraction of the exact image's peak), got -1" \
  conv --steps 0.2,0.1 --invariance-tolerance -1
refuse converge_invariance_huge "--invariance-tolerance: must be in \[0, 1\] (a fraction of the exact image's peak), got 1e+300" \
  conv --steps 0.2,0.1 --invariance-tolerance 1e300
refuse converge_worst_negative "--worst: must be a whole number >= 0, got -1" conv --steps 0.2,0.1 --worst -1
refuse converge_worst_huge "--worst: at most 100000 pixels, got 100001" conv --steps 0.2,0.1 --worst 100001
refuse converge_threads_negative "--threads: must be a whole number >= 0, got -1" conv --steps 0.2,0.1 --threads -1
refuse scene_sweep_threads_negative "--threads: must be a whole number >= 0, got -1" \
  "$rayint" scene-sweep "$src/docs/examples/grid-scene.json" --threads -1 -o out.json -q

# HSV colour maps: colours outside [0, 1] (the cause of the 456 MB import) are refused at the
# field; extreme scalars, log scales and ranges in HSV import at once.
echo '{"Name": "h", "ColorSpace": "HSV", "RGBPoints": [0, 1e300, 0, 0, 1, 0, 0, 1]}' >hsv_huge.json
refuse hsv_huge_colour "hsv_huge.json: RGBPoints\[1\]: colour components must be in \[0, 1\]" \
  "$rayint" tf import hsv_huge.json -o out.json -q
echo '{"Name": "h", "ColorSpace": "HSV", "UseLogScale": true, "RGBPoints": [1e-300, 1, 0, 0, 1e300, 0, 0, 1]}' >hsv_wide.json
if timeout 30 bash -c "$(vlimit 1000000); exec \"$rayint\" tf import hsv_wide.json --range 1e-300 1e300 -o hsv_wide.out.json -q"; then
  echo "ok hsv_wide: an HSV log-scale preset over [1e-300, 1e300] imports within 30 s and 1 GB"
else
  fail "hsv_wide: HSV import over [1e-300, 1e300] failed or took > 30 s / 1 GB"
fi

# Two builds of one version: a shard written by another executable is refused by name.
cp "$rayint" other-rayint && printf 'x' >>other-rayint
./other-rayint stress --count 20 --seed 3 --shard 1/2 -o s1other.json -q || fail "other build shard"
refuse other_build "s1other.json: build: written by another rayint build" "$rayint" merge s0.json s1other.json -o out.json

# A .pvtu's piece files are inputs: a piece edited after the shards ran refuses the merge.
mkdir pv && cp "$src"/tests/fixtures/readers/ghost.pvtu "$src"/tests/fixtures/readers/ghost_[01].vtu pv/
/usr/bin/python3 - <<'PY'
import json
c = json.load(open("small.json"))
c["mesh_file"] = "pv/ghost.pvtu"
c.pop("scalar_field", None)
json.dump(c, open("pvtu.json", "w"))
PY
if "$rayint" render pvtu.json --shard 0/2 -o p0.json -q 2>err && "$rayint" render pvtu.json --shard 1/2 -o p1.json -q 2>>err; then
  echo " " >>pv/ghost_1.vtu
  refuse pvtu_piece_changed "input files changed" "$rayint" merge p0.json p1.json -o out.png
else
  fail "pvtu shards: $(cat err)"
fi

[ "$failures" = 0 ] || { echo "$failures failures"; exit 1; }
echo "all reliability limit cases pass"
