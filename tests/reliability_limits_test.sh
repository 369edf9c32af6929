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
( ulimit -v 600000; "$rayint" render big.json -o out.png -q 2>err; echo $? >rc )
[ "$(cat rc)" = 2 ] || fail "ulimit -v: exit $(cat rc)"
[ "$(wc -l <err)" = 1 ] || { fail "ulimit -v: not one line"; cat err; }
echo "ok ulimit_v: $(cat err)"

[ "$failures" = 0 ] || { echo "$failures failures"; exit 1; }
echo "all reliability limit cases pass"
