#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace shadowlab {
namespace {

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

// Reads exactly `size` bytes from `fd` into `out`; a short read (the file shrank) or one
// more byte (it grew) is an error.
template <class Buffer>
void read_exactly(const std::string& path, int fd, uint64_t size, Buffer& out) {
  out.resize(size_t(size));
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::read(fd, reinterpret_cast<char*>(out.data()) + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(path, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) throw InputError(path, "changed size while being read");
    done += size_t(n);
  }
  char extra = 0;
  ssize_t n = 0;
  do n = ::read(fd, &extra, 1);
  while (n < 0 && errno == EINTR);
  if (n > 0) throw InputError(path, "changed size while being read");
}

}  // namespace

std::string format_byte_limit(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  uint64_t v = bytes;
  while (u < 4 && v >= 1024 && v % 1024 == 0) v /= 1024, ++u;
  return std::to_string(v) + " " + units[u];
}

InputFile::InputFile(const std::string& path, const InputLimit& limit) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw InputError(path, std::string("cannot read: ") + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(path, std::string("is ") + file_type_name(st.st_mode) + ", not a regular file");
  }
  size_ = uint64_t(st.st_size);
  if (size_ > limit.bytes) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(path, "is " + std::to_string(size_) + " bytes, over the limit of " +
                               format_byte_limit(limit.bytes) + " for " + limit.kind);
  }
  // Reads of a regular file never block; blocking mode again for libraries given the descriptor.
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

int InputFile::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

std::string read_input_file(const std::string& path, const InputLimit& limit) {
  InputFile file(path, limit);
  std::string out;
  read_exactly(path, file.fd(), file.size(), out);
  return out;
}

std::vector<unsigned char> read_input_bytes(const std::string& path, const InputLimit& limit) {
  InputFile file(path, limit);
  std::vector<unsigned char> out;
  read_exactly(path, file.fd(), file.size(), out);
  return out;
}

void read_input_file(const std::string& path, const InputLimit& limit, std::vector<char>& out) {
  InputFile file(path, limit);
  read_exactly(path, file.fd(), file.size(), out);
}

void check_input_file(const std::string& path, const InputLimit& limit) { InputFile file(path, limit); }

bool try_read_input_file(const std::string& path, const InputLimit& limit, std::string& out,
                         std::string* why) {
  try {
    out = read_input_file(path, limit);
    return true;
  } catch (const InputError& e) {
    if (why) *why = e.reason;
    return false;
  }
}

}  // namespace shadowlab
