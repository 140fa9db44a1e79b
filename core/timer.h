#pragma once
// Wall-clock timing: milliseconds, median of N repeats.
#include <algorithm>
#include <chrono>
#include <vector>

namespace shadowlab {

// Milliseconds elapsed since `start`.
inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Median of samples (mean of the two middle ones for an even count); 0 for none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The median, smallest and largest of a benchmark's samples (none: all 0).
struct Stat {
  double median = 0.0, min = 0.0, max = 0.0;
};
inline Stat stat_of(const std::vector<double>& v) {
  if (v.empty()) return {};
  return {median(v), *std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end())};
}

// Runs fn() `repeats` times and returns the median wall time in milliseconds.
template <class Fn>
double median_ms(int repeats, Fn&& fn) {
  std::vector<double> t;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    const auto s = std::chrono::steady_clock::now();
    fn();
    t.push_back(ms_since(s));
  }
  return median(t);
}

}  // namespace shadowlab
