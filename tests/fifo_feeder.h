#pragma once
// A FIFO for tests of code that must refuse one without waiting. A program that opened it for
// reading with a blocking open would wait for a writer forever: the feeder is that writer (a
// thread that opens the write end and closes it at once, again after every open by a reader,
// so each blocked reader sees end of file and the test ends on any code). release() stops it:
// it holds a read end open (so the writer's last open returns at once) until the thread ends.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
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
      writer_ = std::thread([this] {
        while (!stop_) {
          const int fd = ::open(path_.c_str(), O_WRONLY);  // waits for a reader
          if (fd < 0) break;
          ::close(fd);
        }
      });
  }
  ~FifoFeeder() { release(); }
  bool ok() const { return ok_; }
  const std::string& path() const { return path_; }
  // Opens the read end without waiting (which lets the writer's open return), then joins.
  void release() {
    if (!writer_.joinable()) return;
    stop_ = true;
    const int fd = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK);
    writer_.join();
    if (fd >= 0) ::close(fd);
    std::filesystem::remove(path_);
  }

 private:
  std::string path_;
  bool ok_ = false;
  std::atomic<bool> stop_{false};
  std::thread writer_;
};

}  // namespace shadowlab::test
