#include "core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "core/timer.h"

namespace shadowlab {
namespace {

// Restores the thread count a test changed.
struct ThreadCountGuard {
  int saved = thread_count();
  ~ThreadCountGuard() { set_thread_count(saved); }
};

TEST(Parallel, ForWritesEveryIndexExactlyOnce) {
  ThreadCountGuard guard;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    EXPECT_EQ(thread_count(), threads);
    const size_t n = 10007;
    std::unique_ptr<std::atomic<int>[]> hits(new std::atomic<int>[n]);
    for (size_t i = 0; i < n; ++i) hits[i] = 0;
    parallel_for(3, n, [&](size_t i) { hits[i].fetch_add(1); });
    for (size_t i = 0; i < n; ++i)
      ASSERT_EQ(hits[i].load(), i < 3 ? 0 : 1) << "index " << i << ", " << threads << " threads";
  }
}

TEST(Parallel, EmptyRangeDoesNothing) {
  int calls = 0;
  parallel_for(5, 5, [&](size_t) { ++calls; });
  parallel_for(6, 5, [&](size_t) { ++calls; });
  parallel_for_chunks(0, 16, [&](size_t, size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(Parallel, ChunksDependOnCountAndGrainOnly) {
  ThreadCountGuard guard;
  std::vector<std::vector<std::pair<size_t, size_t>>> per_threads;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    const size_t count = 1000, grain = 64;
    std::vector<std::pair<size_t, size_t>> chunks((count + grain - 1) / grain);
    parallel_for_chunks(count, grain, [&](size_t b, size_t e) { chunks[b / grain] = {b, e}; });
    for (size_t c = 0; c < chunks.size(); ++c) {
      EXPECT_EQ(chunks[c].first, c * grain);
      EXPECT_EQ(chunks[c].second, std::min(count, (c + 1) * grain));
    }
    per_threads.push_back(chunks);
  }
  EXPECT_EQ(per_threads[0], per_threads[1]);
  EXPECT_EQ(per_threads[0], per_threads[2]);
}

TEST(Parallel, InvalidThreadCountsAreInputErrors) {
  ThreadCountGuard guard;
  EXPECT_THROW(set_thread_count(0), InputError);
  EXPECT_THROW(set_thread_count(-3), InputError);
  EXPECT_THROW(set_thread_count(1025), InputError);
  try {
    set_thread_count(0);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "--threads");
  }
}

TEST(Rng, FloatIsInUnitIntervalAndCountersDiffer) {
  EXPECT_EQ(rng_float(0), 0.0f);
  EXPECT_LT(rng_float(~0ull), 1.0f);
  std::vector<uint64_t> hashes;
  for (uint64_t pixel = 0; pixel < 64; ++pixel)
    for (uint64_t sample = 0; sample < 16; ++sample) {
      const uint64_t h = rng_hash(pixel, sample, 1);
      const float u = rng_float(h);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      hashes.push_back(h);
    }
  std::sort(hashes.begin(), hashes.end());
  EXPECT_EQ(std::adjacent_find(hashes.begin(), hashes.end()), hashes.end()) << "distinct hashes";
  // Neighbouring counters, seeds and dimensions give different floats.
  EXPECT_NE(rng_float(rng_hash(0, 0, 1)), rng_float(rng_hash(1, 0, 1)));
  EXPECT_NE(rng_float(rng_hash(0, 0, 1)), rng_float(rng_hash(0, 1, 1)));
  EXPECT_NE(rng_float(rng_hash(0, 0, 1)), rng_float(rng_hash(0, 0, 2)));
  EXPECT_NE(rng_float(rng_hash(0, 0, 1, 0)), rng_float(rng_hash(0, 0, 1, 1)));
  // Pure function: same inputs, same bits.
  EXPECT_EQ(rng_hash(12, 34, 56, 7), rng_hash(12, 34, 56, 7));
}

TEST(Rng, MeanIsAboutOneHalf) {
  double sum = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) sum += rng_float(rng_hash(uint64_t(i), 0, 42));
  EXPECT_NEAR(sum / n, 0.5, 0.01);  // σ of the mean ≈ 0.0009
}

TEST(Timer, MedianOfHandExamples) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({5.0}), 5.0);
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median({7.0, 7.0, 1.0, 100.0, 7.0}), 7.0);
}

TEST(Timer, MedianMsRunsTheFunctionRepeatTimes) {
  int calls = 0;
  const double ms = median_ms(5, [&] { ++calls; });
  EXPECT_EQ(calls, 5);
  EXPECT_GE(ms, 0.0);
  median_ms(0, [&] { ++calls; });
  EXPECT_EQ(calls, 6) << "at least one repeat";
}

}  // namespace
}  // namespace shadowlab
