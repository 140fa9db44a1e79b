#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.h"

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
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(tmp, "cannot write the " + what);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(path, "cannot move the " + what + " into place: " + ec.message());
  }
}

}  // namespace shadowlab
