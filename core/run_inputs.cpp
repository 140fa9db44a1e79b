#include "core/run_inputs.h"

#include <sys/stat.h>

#include <filesystem>
#include <mutex>
#include <vector>

namespace shadowlab {
namespace {

struct Input {
  std::string given, normalized;
  bool has_id = false;
  dev_t dev = 0;
  ino_t ino = 0;
};

std::mutex& inputs_mutex() {
  static std::mutex m;
  return m;
}

std::vector<Input>& inputs() {
  static std::vector<Input> v;
  return v;
}

}  // namespace

std::string normalized_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? path : p.lexically_normal().string();
}

void note_input(const std::string& path) {
  Input in;
  in.given = path;
  in.normalized = normalized_path(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    in.has_id = true;
    in.dev = st.st_dev;
    in.ino = st.st_ino;
  }
  const std::lock_guard<std::mutex> lock(inputs_mutex());
  inputs().push_back(std::move(in));
}

std::string input_named_by(const std::string& path) {
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  const std::string normalized = normalized_path(path);
  const std::lock_guard<std::mutex> lock(inputs_mutex());
  for (const Input& in : inputs()) {
    if (exists && in.has_id && in.dev == st.st_dev && in.ino == st.st_ino) return in.given;
    if (in.normalized == normalized) return in.given;
  }
  return "";
}

}  // namespace shadowlab
