#pragma once
// The progress line of a run made of steps (sweep rows, tune evaluations): "[done/total] what
// elapsed …, ETA …" on stderr, rewritten in place; only when enabled (stderr is a terminal).
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

#include "core/timer.h"

namespace shadowlab {

inline void step_progress_line(bool enabled, size_t done, size_t total, const std::string& what,
                               std::chrono::steady_clock::time_point start) {
  if (!enabled) return;
  const double elapsed = ms_since(start) / 1000.0;
  const double eta = done == 0 ? 0.0 : elapsed / double(done) * double(total - done);
  std::fprintf(stderr, "\r[%zu/%zu] %-40.40s elapsed %6.1f s, ETA %6.1f s   ", done, total,
               what.c_str(), elapsed, eta);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace shadowlab
