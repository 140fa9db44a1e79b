#pragma once
// A FIFO for tests of code that must refuse one without waiting. A program that opened it for
// reading with a blocking open would wait for a writer forever: the feeder is that writer (a
// thread opening the write end and closing it at once, so a blocked reader sees end of file
// and the test ends either way). release() unblocks the feeder when nothing opened the FIFO.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <thread>

namespace shadowlab::test {

class FifoFeeder {
 public:
  explicit FifoFeeder(std::string path) : path_(std::move(path)) {
    std::filesystem::remove(path_);
    ok_ = ::mkfifo(path_.c_str(), 0600) == 0;
    if (ok_)
      writer_ = std::thread([p = path_] {
        const int fd = ::open(p.c_str(), O_WRONLY);  // waits for any reader
        if (fd >= 0) ::close(fd);
      });
  }
  ~FifoFeeder() { release(); }
  bool ok() const { return ok_; }
  const std::string& path() const { return path_; }
  // Opens the read end without waiting (which lets the writer's open return), then joins.
  void release() {
    if (!writer_.joinable()) return;
    const int fd = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK);
    writer_.join();
    if (fd >= 0) ::close(fd);
    std::filesystem::remove(path_);
  }

 private:
  std::string path_;
  bool ok_ = false;
  std::thread writer_;
};

}  // namespace shadowlab::test
