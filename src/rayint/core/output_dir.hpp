#pragma once
// Output folders named on a command line (`check --artifacts`, `gate --write-baseline`,
// `stress --worst-dir`, `scatter --images`, ...): created when missing, refused only when the
// path exists and is not a folder.
#include <string>

namespace rayint {

// Creates `dir` and its missing parents. Throws InputError "<dir>: <option>: exists and is not a
// directory" when something other than a folder is at that path, or "<dir>: <option>: cannot
// create the directory (<reason>)" when it cannot be made.
void ensure_output_directory(const std::string& dir, const std::string& option);

// For a folder that is read (`gate --baseline`): InputError "<dir>: <option>: no such directory"
// when nothing is there, "<dir>: <option>: exists and is not a directory" when a file is.
void require_input_directory(const std::string& dir, const std::string& option);

}  // namespace rayint
