#pragma once
// Where a test finds the source tree and the `rayint` binary. Both are compiled into one generated
// file (build/tests/test_paths.cpp, tests/CMakeLists.txt) rather than passed to every test as -D
// strings: then no other test object depends on where the tree is checked out, and ccache shares
// them between checkouts (worktrees, CI clones).
#include <string>

namespace rayint_test {
std::string source_dir();
std::string cli_path();
}  // namespace rayint_test

#define RAYINT_SOURCE_DIR (::rayint_test::source_dir())
#define RAYINT_CLI_PATH (::rayint_test::cli_path())
