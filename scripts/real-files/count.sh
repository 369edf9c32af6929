#!/usr/bin/env bash
# Re-counts issue 27's "what real tools write" figures: makes the corpus with the real tools
# (make-corpus.sh: gmsh, TetGen, meshio, VTK 9.1, ParaView 5.11) unless one is given, then runs the
# rayint binary on every file (count.py) and prints the Markdown summary.
#
#   scripts/real-files/count.sh RAYINT [CORPUS_DIR] [count.py options, e.g. -o results.json --jobs 2]
#
# CORPUS_DIR without a manifest.json: the corpus is made there (and kept); with one: it is counted
# as it is. Without CORPUS_DIR a fresh corpus is made in a temporary folder and removed afterwards.
# Then crosscheck_vtk.py compares rayint's integrals with an independent route on VTK's reading
# (NO_CROSSCHECK=1 skips it). About 1 min to generate, 2 min to count, 0.5 min to cross-check on
# 2 busy cores.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
[ $# -ge 1 ] || { echo "usage: $0 RAYINT [CORPUS_DIR] [-o results.json] [--jobs N]" >&2; exit 2; }
rayint="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
shift
[ -x "$rayint" ] || { echo "count.sh: $rayint is not an executable" >&2; exit 2; }
corpus=""
if [ $# -ge 1 ] && [ "${1#-}" = "$1" ]; then corpus="$1"; shift; fi
keep=1
if [ -z "$corpus" ]; then
  corpus="$(mktemp -d /tmp/rayint-corpus.XXXXXX)"
  keep=0
  trap 'rm -rf "$corpus"' EXIT
fi
if [ ! -f "$corpus/manifest.json" ]; then
  "$here/make-corpus.sh" "$corpus" > /dev/null 2> "$corpus.make.log" || { cat "$corpus.make.log" >&2; exit 1; }
  rm -f "$corpus.make.log"
fi
[ -f "$corpus/manifest.json" ] || { echo "count.sh: $corpus/manifest.json missing (run make-corpus.sh $corpus)" >&2; exit 2; }
# count.py's per-file results go to -o FILE if given, else to a temporary file for the cross-check
results=""
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case "${args[$i]}" in -o|--output) results="${args[$((i + 1))]:-}" ;; esac
done
if [ -z "$results" ]; then
  results="$(mktemp /tmp/rayint-count.XXXXXX.json)"
  args+=(-o "$results")
  trap 'rm -f "$results"; [ "${keep:-1}" = 1 ] || rm -rf "$corpus"' EXIT
fi
/usr/bin/python3 "$here/count.py" "$rayint" "$corpus" "${args[@]}"
if [ "${NO_CROSSCHECK:-0}" != 1 ]; then
  echo
  echo "### rayint's integrals against an independent route on VTK's own reading (crosscheck_vtk.py)"
  echo
  /usr/bin/python3 "$here/crosscheck_vtk.py" "$results" 2>/dev/null
fi
