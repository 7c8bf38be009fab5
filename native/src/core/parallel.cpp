#include "anisomesh/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace anisomesh {
namespace {

std::atomic<int> gThreads{1};
#if defined(__EMSCRIPTEN__)
constexpr bool kSingleThreaded = true;  // no -pthread build: one thread, the same chunks
#else
constexpr bool kSingleThreaded = false;
#endif

}  // namespace

int threadCount() { return gThreads.load(std::memory_order_relaxed); }

void setThreadCount(int threads) {
#if defined(__EMSCRIPTEN__)
  (void)threads;
  gThreads = 1;
#else
  gThreads = std::max(1, std::min(256, threads));
#endif
}

void parallelChunks(size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& f) {
  if (n == 0) return;
  if (grain == 0) grain = 1;
  const size_t chunks = chunkCount(n, grain);
  const size_t workers = std::min<size_t>(size_t(threadCount()), chunks);
  if (workers <= 1 || kSingleThreaded) {
    for (size_t c = 0; c < chunks; ++c) f(c, c * grain, std::min(n, (c + 1) * grain));
    return;
  }
  std::atomic<size_t> next{0};
  std::mutex m;
  size_t failedChunk = chunks;
  std::exception_ptr failure;
  auto work = [&] {
    for (size_t c; (c = next.fetch_add(1)) < chunks;) {
      try {
        f(c, c * grain, std::min(n, (c + 1) * grain));
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (c < failedChunk) failedChunk = c, failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b) {
  if (threadCount() <= 1 || kSingleThreaded) {
    a();
    b();
    return;
  }
  std::exception_ptr fb;
  std::thread t([&] {
    try {
      b();
    } catch (...) {
      fb = std::current_exception();
    }
  });
  std::exception_ptr fa;
  try {
    a();
  } catch (...) {
    fa = std::current_exception();
  }
  t.join();
  if (fa) std::rethrow_exception(fa);
  if (fb) std::rethrow_exception(fb);
}

}  // namespace anisomesh
