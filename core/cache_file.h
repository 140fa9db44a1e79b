#pragma once
// Cache files (the reference cache, the LOD cache): whole-file reads, and writes that a reader
// never sees half done — a uniquely named temporary in the same folder (same file system),
// then renamed into place (atomic on POSIX).
#include <cstddef>
#include <string>
#include <vector>

namespace shadowlab {

// Creates `dir` if needed and writes `bytes` to `path` atomically. `what` names the file kind
// in errors ("reference cache file"). Throws InputError naming the folder or file on failure
// (the temporary is removed).
void write_file_atomically(const std::string& dir, const std::string& path,
                           const std::vector<char>& bytes, const std::string& what);

// Whether files can be created in `dir` (created if needed): a probe file is written and
// removed. On false, `reason` says why (the OS's words).
bool folder_is_writable(const std::string& dir, std::string& reason);

// Reads the whole file into `out`; false when it cannot be opened or read or is shorter than
// min_bytes (a cache miss, never an error).
bool read_file_bytes(const std::string& path, size_t min_bytes, std::vector<char>& out);

}  // namespace shadowlab
