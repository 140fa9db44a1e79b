#include "core/progress.h"

#include <cstdio>

namespace shadowlab {

ProgressLine::ProgressLine(std::string label, size_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled) {
  start_ = last_ = std::chrono::steady_clock::now();
}

ProgressLine::~ProgressLine() {
  if (enabled_) print(done_.load(), true);
}

void ProgressLine::advance(size_t n) {
  const size_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  print(done, false);
}

void ProgressLine::print(size_t done, bool final) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double frac = total_ == 0 ? 1.0 : double(done) / double(total_);
  const double eta = frac > 0.0 ? elapsed * (1.0 - frac) / frac : 0.0;
  std::fprintf(stderr, "\r%-32s %5.1f%%  elapsed %6.1f s  ETA %6.1f s ", label_.c_str(),
               100.0 * frac, elapsed, eta);
  if (final) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace shadowlab
