// TSan-visible replacement of cv::parallel_for_ (LD_PRELOAD): Debian's OpenCV
// runs parallel_for_ on libtbb, whose synchronisation TSan cannot see, so
// every hand-off to a worker looks like a race. This runs the same stripes
// (OpenCV 4.6's ParallelLoopBodyWrapperContext arithmetic) on std::threads
// (pthread_create/join, which TSan sees), the caller taking stripes too, and
// like OpenCV runs a nested call serially. NERV_TSAN_SHIM_THREADS=N: up to N
// threads whatever cv::getNumThreads() says (> 1), so more stripe pairs run on
// distinct threads and are checked against each other. NERV_TSAN_SHIM_STATS=1:
// at exit, how many calls ran in parallel and how many of their stripes ran
// on a pool thread (evidence that the checked stripes did run concurrently).
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace {
std::atomic<long> g_calls{0}, g_parallel_calls{0}, g_stripes{0}, g_pool_stripes{0}, g_calls_both{0};
struct Stats {
  ~Stats() {
    const char* e = std::getenv("NERV_TSAN_SHIM_STATS");
    if (e && *e == '1')
      std::fprintf(stderr, "[parallel_for_ shim] calls %ld, parallel %ld (with stripes on >1 thread: %ld), stripes %ld, on pool threads %ld\n",
                   g_calls.load(), g_parallel_calls.load(), g_calls_both.load(), g_stripes.load(), g_pool_stripes.load());
  }
} g_stats;
}  // namespace

namespace cv {

void parallel_for_(const Range& range, const ParallelLoopBody& body, double nstripes) {
  static std::atomic<bool> nested{false};
  if (range.empty()) return;
  g_calls.fetch_add(1, std::memory_order_relaxed);
  const int threads = cv::getNumThreads();
  const int len = range.end - range.start;
  if (threads <= 1 || len <= 1 || nested.exchange(true)) {
    body(range);
    return;
  }
  const int stripes = cvRound(nstripes <= 0 ? double(len) : std::min(std::max(nstripes, 1.0), double(len)));
  if (stripes <= 1) {
    body(range);
    nested = false;
    return;
  }
  auto stripe = [&](int s) {
    Range r;
    r.start = int(range.start + (uint64_t(s) * len + stripes / 2) / stripes);
    r.end = s + 1 >= stripes ? range.end : int(range.start + (uint64_t(s + 1) * len + stripes / 2) / stripes);
    return r;
  };
  // Relaxed: the counter must not order one stripe after another for TSan.
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::atomic<int> pool_done{0};
  auto work = [&](bool pool) {
    for (int s; (s = next.fetch_add(1, std::memory_order_relaxed)) < stripes;) {
      if (pool) pool_done.fetch_add(1, std::memory_order_relaxed);
      try {
        const Range r = stripe(s);
        if (!r.empty()) body(r);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  static const int override_threads = [] {
    const char* e = std::getenv("NERV_TSAN_SHIM_THREADS");
    return e ? std::atoi(e) : 0;
  }();
  const int pool_size = std::min(override_threads > 0 ? override_threads : threads, stripes);
  std::vector<std::thread> pool;
  for (int i = 1; i < pool_size; ++i) pool.emplace_back(work, true);
  work(false);
  for (auto& t : pool) t.join();
  g_parallel_calls.fetch_add(1, std::memory_order_relaxed);
  g_stripes.fetch_add(stripes, std::memory_order_relaxed);
  g_pool_stripes.fetch_add(pool_done.load(), std::memory_order_relaxed);
  if (pool_done.load() > 0 && pool_done.load() < stripes) g_calls_both.fetch_add(1, std::memory_order_relaxed);
  nested = false;
  if (error) std::rethrow_exception(error);
}

}  // namespace cv
