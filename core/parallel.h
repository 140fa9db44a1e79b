#pragma once
// All threading goes through this header (style.md #5). Kernels receive index ranges and never
// see TBB. The thread count comes from set_thread_count (--threads N) or the environment
// variable SHADOWLAB_THREADS, else the machine's core count. Work is split into fixed chunks
// whose boundaries do not depend on the thread count, so outputs never depend on it either.
#include <cstddef>
#include <functional>

namespace shadowlab {

// Sets the number of worker threads (>= 1). Throws InputError for n < 1 or n > 1024.
void set_thread_count(int n);
// Current worker-thread count.
int thread_count();

// Calls body(i) for every i in [begin, end), in parallel. body must only write to data owned
// by index i.
void parallel_for(size_t begin, size_t end, const std::function<void(size_t)>& body);

// Calls body(chunk_begin, chunk_end) over [0, count) split in chunks of `grain` (the last one
// shorter). Chunk boundaries depend on count and grain only.
void parallel_for_chunks(size_t count, size_t grain,
                         const std::function<void(size_t, size_t)>& body);

}  // namespace shadowlab
