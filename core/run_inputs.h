#pragma once
// The files a run reads, noted where they are opened, so that no output of the run can name one
// (docs/bad_input.md "Output paths"). A path names an input when it is the same file (device and
// inode) or, for a path that does not exist, the same normalized absolute path.
#include <string>

namespace shadowlab {

// Records `path` as an input of this process's run (thread-safe; cheap: one stat).
void note_input(const std::string& path);

// The input (as it was given) that `path` names, or "" when it names none.
std::string input_named_by(const std::string& path);

// `path` as an absolute path without ".", ".." and repeated separators, symbolic links of its
// existing folders resolved (std::filesystem::weakly_canonical); `path` itself on failure.
std::string normalized_path(const std::string& path);

}  // namespace shadowlab
