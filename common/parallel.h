// Independent tasks run on several threads, their results taken in task
// order: a search or a sweep gives the same output whatever the number of
// threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>
#endif
#ifdef __linux__
#include <sched.h>
#endif

namespace m4mesh {

// A program's threads allocate from one heap (glibc's arenas): blocks one
// worker frees, another reuses, where an arena per thread keeps its own
// (cpca-wpt's peak resident memory on 10^7 vertex-frames: 955 → 722 MB).
inline void use_one_heap() {
#ifdef __GLIBC__
  mallopt(M_ARENA_MAX, 1);
#endif
}

// The cores this process may run on: its affinity mask's (taskset, a
// container's CPU set) where the system has one, else every core.
inline unsigned available_cores() {
#ifdef __linux__
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

// The threads to run on: `threads`, or one per available core for 0.
inline unsigned worker_count(unsigned threads) { return threads > 0 ? threads : available_cores(); }

// Runs task(i) for every i below `count` on up to worker_count(threads)
// threads, and finished(i) for each i in increasing order as soon as
// tasks 0 … i are done (one at a time). The first exception by task
// order is rethrown once every running task has ended; no task starts
// after one failed.
inline void parallel_for(size_t count, unsigned threads, const std::function<void(size_t)>& task,
                         const std::function<void(size_t)>& finished = nullptr) {
  std::vector<std::exception_ptr> errors(count);
  std::vector<char> done(count, 0);
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex order;
  size_t reported = 0;
  auto work = [&] {
    for (size_t i; !failed && (i = next++) < count;) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
        failed = true;
      }
      const std::lock_guard<std::mutex> lock(order);
      done[i] = 1;
      for (; reported < count && done[reported] && !errors[reported]; ++reported)
        if (finished && !failed) finished(reported);
    }
  };
  const size_t workers = std::min<size_t>(worker_count(threads), count);
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace m4mesh
