#!/usr/bin/env bash
# Fuzzes one parser with libFuzzer + ASan + UBSan for a bounded time, then prints the executions
# and findings. Targets (RAYINT_FUZZ_TARGET): case_parser (rayint::parse_case_text, the default),
# candidate_parser, scene_parser (rayint::parse_scene_text), vtk_legacy (rayint::parse_vtk_legacy),
# gmsh (rayint::parse_gmsh), tetgen (rayint::parse_tetgen). Needs clang and libFuzzer: Debian's
# clang + libclang-rt-14-dev (installed below when missing).
#
#   scripts/fuzz.sh [SECONDS] [extra libFuzzer flags...]     (SECONDS defaults to 60)
#
# Configures its own clang build directory (RAYINT_FUZZ_BUILD_DIR, default build-fuzz/), builds
# fuzz/<target>_fuzzer, seeds it (case_parser: cases/*.json, copied at run time;
# candidate_parser: fuzz/seeds/candidate/) with the dictionary fuzz/<target>.dict, and keeps the
# inputs it finds interesting in RAYINT_FUZZ_CORPUS (default fuzz-corpus/<target>/, reused by the
# next run). Seeds: case_parser cases/*.json; candidate_parser fuzz/seeds/candidate/; scene_parser
# cases/scenes/*.json; vtk_legacy fuzz/seeds/vtk_legacy/ + cases/meshes/linear-box.vtk + the
# meshio .vtk fixtures + tests/fixtures/readers/*.vtk (boundary cells, cell data, float ASCII,
# STRUCTURED_POINTS); gmsh tests/fixtures/meshes/*.msh + tests/fixtures/readers/*.msh (boundary
# cells, 10-node tets); vtu_reader / vti_reader also tests/fixtures/readers/ (LZ4, LZMA, ghost
# pieces, cell data); tetgen fuzz/seeds/tetgen/.
# RAYINT_FUZZ_TARGET selects the target (default case_parser); preset_parser (ParaView presets)
# seeds from fuzz/seeds/preset/; method_spec (parse_method_spec) from fuzz/seeds/method_spec/.
# The image readers pfm_reader, exr_reader, npy_reader seed from fuzz/seeds/<format>/;
# shard_reader (the shard data `rayint merge` reads) from fuzz/seeds/shard/; slab_scene_parser
# (rayint::parse_slab_scene) from cases/scenes/slab-*.json and fuzz/seeds/slab_scene/;
# parallel_grid (rayint::parse_pvts / parse_pvtr: a parallel file and its pieces joined by
# "--piece--" lines, fuzz/parallel_grid_fuzzer.cpp) from fuzz/seeds/parallel_grid/.
# One fuzzing process. Artifacts (crash-*, leak-*, timeout-*, oom-*) and the full log go to
# <build>/artifacts/<target>-<date>/; reproduce one with `<build>/fuzz/<target>_fuzzer <artifact>`.
# Exit status: 0 no findings, 1 findings, 2 usage or build error.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
[ $# -gt 0 ] && shift
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "usage: scripts/fuzz.sh [SECONDS>0] [libFuzzer flags...]" >&2
  exit 2
fi
target="${RAYINT_FUZZ_TARGET:-case_parser}"
case "$target" in
  case_parser) seed_files=("$root"/cases/*.json); what="rayint::parse_case_text" ;;
  candidate_parser) seed_files=("$root"/fuzz/seeds/candidate/*.json); what="rayint::parse_candidate_text" ;;
  grad_candidate_parser) seed_files=("$root"/fuzz/seeds/grad_candidate/*.json); what="rayint::parse_grad_candidate_text" ;;
  vtu_reader) seed_files=("$root"/tests/fixtures/vtkxml/*.vtu "$root"/tests/fixtures/readers/*.vtu); what="rayint::parse_vtu" ;;
  vti_reader) seed_files=("$root"/tests/fixtures/vtkxml/*.vti "$root"/tests/fixtures/readers/*.vti); what="rayint::parse_vti" ;;
  structured_grid) seed_files=("$root"/tests/fixtures/readers/*.vts "$root"/tests/fixtures/readers/*.vtr); what="rayint::parse_vts / parse_vtr" ;;
  parallel_grid) seed_files=("$root"/fuzz/seeds/parallel_grid/*); what="rayint::parse_pvts / parse_pvtr" ;;
  scene_parser) seed_files=("$root"/cases/scenes/*.json); what="rayint::parse_scene_text" ;;
  slab_scene_parser) seed_files=("$root"/cases/scenes/slab-*.json "$root"/fuzz/seeds/slab_scene/*.json); what="rayint::parse_slab_scene" ;;
  vtk_legacy) seed_files=("$root"/fuzz/seeds/vtk_legacy/* "$root"/cases/meshes/linear-box.vtk
                          "$root"/tests/fixtures/meshes/*.vtk "$root"/tests/fixtures/readers/*.vtk)
              what="rayint::parse_vtk_legacy and parse_vtk_legacy_image" ;;
  gmsh) seed_files=("$root"/tests/fixtures/meshes/*.msh "$root"/tests/fixtures/readers/*.msh); what="rayint::parse_gmsh" ;;
  tetgen) seed_files=("$root"/fuzz/seeds/tetgen/*); what="rayint::parse_tetgen" ;;
  preset_parser) seed_files=("$root"/fuzz/seeds/preset/*.json); what="rayint::import_paraview_preset_text" ;;
  method_spec) seed_files=("$root"/fuzz/seeds/method_spec/*); what="rayint::parse_method_spec" ;;
  shard_reader) seed_files=("$root"/fuzz/seeds/shard/*.json); what="rayint shard data readers (rayint merge)" ;;
  pfm_reader|exr_reader|npy_reader)  # float image readers of check --candidate-image; no dictionary
    fmt="${target%_reader}"; seed_files=("$root"/fuzz/seeds/"$fmt"/*); what="rayint::decode_$fmt" ;;
  *) echo "fuzz.sh: RAYINT_FUZZ_TARGET must be case_parser, candidate_parser, grad_candidate_parser, vtu_reader, vti_reader, structured_grid, parallel_grid, scene_parser, slab_scene_parser, vtk_legacy, gmsh, tetgen, preset_parser, method_spec, pfm_reader, exr_reader, npy_reader or shard_reader" >&2; exit 2 ;;
esac
build="${RAYINT_FUZZ_BUILD_DIR:-$root/build-fuzz}"
corpus="${RAYINT_FUZZ_CORPUS:-$root/fuzz-corpus/$target}"
# clang and its libFuzzer/sanitizer runtimes, from Debian's packages, only if missing.
for p in clang libclang-rt-14-dev; do
  dpkg -s "$p" >/dev/null 2>&1 && continue
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$p" >&2
done
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found after installing clang" >&2; exit 2; }

mkdir -p "$build"
# RAYINT_FUZZ_NO_BUILD=1: run the fuzzer already built in $build (e.g. while a build of other
# targets runs in the same directory, which a second configure would disturb).
if [ "${RAYINT_FUZZ_NO_BUILD:-0}" = 1 ]; then
  [ -x "$build/fuzz/${target}_fuzzer" ] || { echo "fuzz.sh: $build/fuzz/${target}_fuzzer not built" >&2; exit 2; }
else
# -O1 with line tables only (libFuzzer's advice: -O1 or more): the instrumented library compiles
# in about half the time of -O2 -g, and stack traces still name file and line. ccache when present.
launcher=(); command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
build_log="$build/fuzz-build.log"
if ! { cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
         -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
         "${launcher[@]}" -DRAYINT_BUILD_FUZZERS=ON -DRAYINT_BUILD_PYTHON=OFF -DRAYINT_BUILD_TESTS=OFF \
         -DRAYINT_BUILD_CLI=OFF -DRAYINT_BUILD_BENCHMARKS=OFF &&
       cmake --build "$build" --target "${target}_fuzzer" -j "$(nproc)"; } >"$build_log" 2>&1; then
  tail -n 30 "$build_log" >&2
  echo "fuzz.sh: building ${target}_fuzzer failed (log: $build_log)" >&2
  exit 2
fi
fi
fuzzer="$build/fuzz/${target}_fuzzer"

seeds="$build/seed-corpus/$target"
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus"
cp "${seed_files[@]}" "$seeds/"
artifacts="$build/artifacts/$target-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$artifacts"
log="$artifacts/fuzz.log"

echo "fuzz.sh: fuzzing $what for ${seconds} s" \
     "(seeds: $(ls "$seeds" | wc -l) files, corpus: $corpus, log: $log)"
set +e
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
dict=(); [ -f "$root/fuzz/$target.dict" ] && dict=(-dict="$root/fuzz/$target.dict")
"$fuzzer" "$corpus" "$seeds" "${dict[@]}" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$artifacts/" "$@" >"$log" 2>&1
status=$?
set -e

final_stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -n 1; }
runs="$(final_stat number_of_executed_units)"
last="$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)"
findings=()
for f in "$artifacts"/crash-* "$artifacts"/leak-* "$artifacts"/timeout-* "$artifacts"/oom-*; do
  [ -e "$f" ] && findings+=("$f")
done
echo "fuzz.sh: executions: ${runs:-unknown}, exec/s: $(final_stat average_exec_per_sec)," \
     "peak RSS: $(final_stat peak_rss_mb) MB, corpus: $(ls "$corpus" | wc -l) inputs"
echo "fuzz.sh: last status: ${last:-none}"
if [ ${#findings[@]} -gt 0 ] || [ "$status" -ne 0 ]; then
  echo "fuzz.sh: FINDINGS (libFuzzer exit status $status):"
  for f in "${findings[@]}"; do echo "  $f"; done
  grep -m 5 -E 'ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error:|deadly signal|uncaught exception' "$log" | sed 's/^/  /' || true
  echo "fuzz.sh: reproduce with: $fuzzer <artifact>; full log: $log"
  exit 1
fi
echo "fuzz.sh: no findings"
