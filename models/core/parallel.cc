// The thread count and the deterministic parallel loop over oneTBB.
#include "models/core/parallel.h"

#include <exception>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "models/core/error.h"

namespace waam {
namespace {

std::mutex g_thread_mutex;
std::unique_ptr<tbb::global_control> g_thread_limit;  // null: TBB's default, all hardware threads
int g_threads = 0;                                   // 0: all hardware threads

}  // namespace

void SetThreadCount(int threads) {
  WAAM_THROW_UNLESS(threads >= 0, "thread count " << threads << ": must be >= 0 (0 = all hardware threads)");
  std::lock_guard<std::mutex> lock(g_thread_mutex);
  g_threads = threads;
  g_thread_limit.reset();
  if (threads > 0) {
    g_thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                           static_cast<std::size_t>(threads));
  }
}

int ThreadCount() {
  std::lock_guard<std::mutex> lock(g_thread_mutex);
  return g_threads > 0 ? g_threads : tbb::info::default_concurrency();
}

void ParallelFor(std::size_t n, const std::function<void(std::size_t)>& body) {
  if (n == 0) return;
  if (n == 1 || ThreadCount() == 1) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  // Every index runs; each keeps its own exception, and the lowest index's is rethrown.
  std::vector<std::exception_ptr> errors(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      try {
        body(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace waam
