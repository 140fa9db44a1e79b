#include "core/output_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/temp_cleanup.h"

namespace shadowlab {

namespace {

std::function<void(const std::string&)>& commit_check() {
  static std::function<void(const std::string&)> check;
  return check;
}

}  // namespace

void set_commit_check(std::function<void(const std::string& path)> check) {
  commit_check() = std::move(check);
}

OutputFile::OutputFile(std::string path)
    : path_(std::move(path)), temp_(path_ + ".partial-" + std::to_string(::getpid())) {
  register_temporary(temp_);
}

OutputFile::~OutputFile() {
  if (!committed_) std::remove(temp_.c_str());
  unregister_temporary(temp_);
}

void OutputFile::commit() {
  if (commit_check()) commit_check()(path_);
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    throw InputError(path_, std::string("cannot write: ") + std::strerror(errno));
  committed_ = true;
  unregister_temporary(temp_);
}

void write_text_file(const std::string& path, const std::string& text) {
  OutputFile out(path);
  std::FILE* f = std::fopen(out.temp_path().c_str(), "wb");
  if (!f) throw InputError(path, std::string("cannot write: ") + std::strerror(errno));
  const size_t written = std::fwrite(text.data(), 1, text.size(), f);
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (written != text.size() || !flushed || !closed)
    throw InputError(path, std::string("cannot write: ") +
                               std::strerror(written != text.size() ? write_errno : flush_errno));
  out.commit();
}

}  // namespace shadowlab
