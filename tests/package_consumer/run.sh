#!/usr/bin/env bash
# usage: run.sh BUILD_DIR WORK_DIR SOURCE_DIR -- install rayint from BUILD_DIR, build the consumer.
set -euo pipefail
build="$1"; work="$2"; src="$3"
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$src/tests/package_consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer"
