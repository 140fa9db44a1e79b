#include "core/parallel.h"

#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/parse_number.h"

namespace shadowlab {
namespace {

int initial_thread_count() {
  if (const char* env = std::getenv("SHADOWLAB_THREADS"); env && *env) {
    // The rules of --threads (core/parse_number.h: no spaces, no '+'); the programs check the
    // variable before any work (lab/environment.h), this guards every other caller.
    long n = 0;
    if (!parse_long(env, n) || n < 1 || n > 1024)
      throw InputError("SHADOWLAB_THREADS", std::string("expected an integer in [1, 1024], got '") +
                                                env + "'");
    return int(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : int(hw);
}

struct ArenaState {
  std::mutex mutex;
  int count = 0;
  std::unique_ptr<tbb::global_control> limit;
  std::unique_ptr<tbb::task_arena> arena;
};

ArenaState& state() {
  static ArenaState s;
  return s;
}

tbb::task_arena& arena() {
  ArenaState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.arena) {
    if (s.count == 0) s.count = initial_thread_count();
    // Raise TBB's global worker limit to the requested count, which may exceed the core count
    // (determinism tests run 7 threads on 2 cores).
    s.limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    size_t(s.count));
    s.arena = std::make_unique<tbb::task_arena>(s.count);
  }
  return *s.arena;
}

}  // namespace

void set_thread_count(int n) {
  if (n < 1 || n > 1024)
    throw InputError("--threads", "expected an integer in [1, 1024], got " + std::to_string(n));
  ArenaState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.count = n;
  s.arena.reset();
  s.limit.reset();
}

int thread_count() {
  arena();
  return state().count;
}

void parallel_for(size_t begin, size_t end, const std::function<void(size_t)>& body) {
  if (end <= begin) return;
  arena().execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
  });
}

void parallel_for_chunks(size_t count, size_t grain,
                         const std::function<void(size_t, size_t)>& body) {
  if (count == 0) return;
  if (grain == 0) grain = 1;
  const size_t chunks = (count + grain - 1) / grain;
  parallel_for(0, chunks, [&](size_t c) {
    const size_t b = c * grain;
    const size_t e = b + grain < count ? b + grain : count;
    body(b, e);
  });
}

}  // namespace shadowlab
