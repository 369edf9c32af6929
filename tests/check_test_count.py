#!/usr/bin/python3
"""CTest test `test_count_matches_discovery`: every Catch2 TEST_CASE compiled in must be a CTest test.

usage: check_test_count.py CTEST BUILD_DIR EXE=TEST_PREFIX [EXE=TEST_PREFIX ...]

catch_discover_tests (Catch2 2.13) turns the output of `EXE --list-test-names-only` into a CMake
list, so a test name containing ';' (or an unbalanced '[') is split or merged into names that run
nothing -- silently. This compares, per executable, Catch's own listing with the tests CTest runs
for it (`ctest --show-only=json-v1`, matched on the executable) and fails with one line if the
counts or the names differ. Both sides leave out hidden tests ('[.]', '[!hide]', names starting
with './'): discovery is given no test spec, so it sees exactly what the listing prints.
"""
import json
import os
import subprocess
import sys


def main(argv):
    if len(argv) < 4 or not all("=" in a for a in argv[3:]):
        sys.exit("usage: check_test_count.py CTEST BUILD_DIR EXE=TEST_PREFIX [EXE=TEST_PREFIX ...]")
    ctest, build = argv[1], argv[2]
    shown = subprocess.run([ctest, "--test-dir", build, "--show-only=json-v1"],
                           capture_output=True, text=True, check=True).stdout
    ctest_tests = json.loads(shown)["tests"]
    failures = []
    for exe, _, prefix in (a.rpartition("=") for a in argv[3:]):
        # The exit code of --list-test-names-only is the number of tests (mod 256), not an error.
        listed = subprocess.run([exe, "--list-test-names-only"], capture_output=True, text=True)
        if listed.returncode < 0:
            sys.exit(f"test count check: {exe} --list-test-names-only died ({listed.returncode})")
        catch_names = [prefix + n for n in listed.stdout.splitlines() if n]
        real = os.path.realpath(exe)
        ctest_names = [t["name"] for t in ctest_tests
                       if t.get("command") and os.path.realpath(t["command"][0]) == real]
        if sorted(catch_names) != sorted(ctest_names):
            not_run = sorted(set(catch_names) - set(ctest_names))
            extra = sorted(set(ctest_names) - set(catch_names))
            failures.append(
                f"{os.path.basename(exe)}: {len(catch_names)} TEST_CASEs vs {len(ctest_names)} "
                f"CTest tests; not run by CTest: {not_run}; "
                f"CTest tests that are no TEST_CASE: {extra} (';' or '[' in a test name?)")
        else:
            print(f"{os.path.basename(exe)}: {len(catch_names)} TEST_CASEs, "
                  f"{len(ctest_names)} CTest tests")
    for f in failures:
        print("test count mismatch: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
