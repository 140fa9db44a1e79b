#pragma once
// A progress line with an ETA on stderr for long work (references, sweeps). Shown only when
// enabled (the mains enable it when stderr is a terminal); thread-safe and throttled to a few
// updates per second, so kernels may report from any worker. It never affects results.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace shadowlab {

class ProgressLine {
 public:
  ProgressLine(std::string label, size_t total, bool enabled);
  ~ProgressLine();  // finishes the line
  // Adds `n` finished units (thread-safe).
  void advance(size_t n = 1);
  bool enabled() const { return enabled_; }

 private:
  void print(size_t done, bool final);
  std::string label_;
  size_t total_;
  bool enabled_;
  std::atomic<size_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace shadowlab
