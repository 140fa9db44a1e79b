#pragma once
// Writing cache files so a reader never sees half a file: write a uniquely named temporary in
// the same folder (same file system), then rename it into place (atomic on POSIX).
#include <string>
#include <vector>

namespace shadowlab {

// Creates `dir` if needed and writes `bytes` to `path` atomically. `what` names the file kind
// in errors ("reference cache file"). Throws InputError naming the folder or file on failure
// (the temporary is removed).
void write_file_atomically(const std::string& dir, const std::string& path,
                           const std::vector<char>& bytes, const std::string& what);

}  // namespace shadowlab
