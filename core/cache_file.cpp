#include "core/cache_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"
#include "core/input_file.h"
#include "core/temp_cleanup.h"

namespace shadowlab {

void write_file_atomically(const std::string& dir, const std::string& path,
                           const std::vector<char>& bytes, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the folder of the " + what + ": " + ec.message());
  // Unique temporary name in the same folder (same file system, so rename is atomic).
  static std::atomic<uint64_t> counter{0};
  const std::string tmp = path + ".tmp." + std::to_string(uint64_t(::getpid())) + "." +
                          std::to_string(counter.fetch_add(1));
  // Removed on an interrupt too (core/temp_cleanup.h): a reader never sees it either way.
  register_temporary(tmp);
  struct Unregister {
    const std::string& path;
    ~Unregister() { unregister_temporary(path); }
  } unregister{tmp};
  {
    // errno read right after the step that failed: the OS's reason (a full disk, a missing
    // folder, permissions) goes into the message.
    int err = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) err = errno;
    if (out) out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out && err == 0) err = errno;
    out.close();
    if (!out && err == 0) err = errno;
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(tmp, "cannot write the " + what + ": " +
                                std::generic_category().message(err != 0 ? err : EIO));
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(path, "cannot move the " + what + " into place: " + ec.message());
  }
}

bool read_file_bytes(const std::string& path, size_t min_bytes, std::vector<char>& out) {
  // Not a regular file (a FIFO would block, /dev/zero never end), over kCacheFileLimit,
  // missing or unreadable: a miss, and the cache is recomputed.
  try {
    read_input_file(path, kCacheFileLimit, out);
    return out.size() >= min_bytes;
  } catch (const InputError&) {
    return false;
  }
}

bool folder_is_writable(const std::string& dir, std::string& reason) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    reason = ec.message();
    return false;
  }
  const std::string probe = dir + "/.write_probe_" + std::to_string(::getpid());
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) {
    reason = std::strerror(errno);
    return false;
  }
  std::fclose(f);
  std::remove(probe.c_str());
  return true;
}

}  // namespace shadowlab
