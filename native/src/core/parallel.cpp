#include "anisomesh/core/parallel.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace anisomesh {
namespace {

std::atomic<int> gThreads{1};
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
constexpr bool kSingleThreaded = true;  // no -pthread build: one thread, the same chunks
constexpr int kMaxThreads = 1;
#elif defined(__EMSCRIPTEN_PTHREADS__)
constexpr bool kSingleThreaded = false;
// The caller and the most workers wasm/threads_pre.js starts with the module (the bindings'
// setThreads clamps to the pool actually started: a thread beyond it would wait for the
// caller's event loop).
constexpr int kMaxThreads = 8;
#else
constexpr bool kSingleThreaded = false;
constexpr int kMaxThreads = 256;
#endif
// True on the threads this layer starts. In the Emscripten pthreads build they run nested
// calls on themselves: a thread started from a worker is created by the main runtime
// thread's event loop, which a blocking join never returns to (the result is the same).
thread_local bool tWorker = false;
#if defined(__EMSCRIPTEN_PTHREADS__)
bool nestedRunsSerially() { return tWorker; }
#else
bool nestedRunsSerially() { return false; }
#endif

thread_local bool tInsideChunks = false;
thread_local int tSlot = 0;

// The slot numbers in use (0 is every thread the layer did not start).
std::mutex gSlotsLock;
std::array<bool, kThreadSlots> gSlotsUsed{};

// Holds a free slot for the thread that constructs it, until it is destroyed.
class SlotHold {
 public:
  SlotHold() {
    std::lock_guard<std::mutex> lock(gSlotsLock);
    int s = 1;
    while (s < kThreadSlots && gSlotsUsed[size_t(s)]) ++s;
    // More live threads than slots: the layer never starts that many (at most threadCount()
    // per region, nested regions run on their caller's thread).
    if (s == kThreadSlots) std::terminate();
    gSlotsUsed[size_t(s)] = true;
    tSlot = s;
  }
  ~SlotHold() {
    std::lock_guard<std::mutex> lock(gSlotsLock);
    gSlotsUsed[size_t(tSlot)] = false;
  }
  SlotHold(const SlotHold&) = delete;
  SlotHold& operator=(const SlotHold&) = delete;
};

// Marks the calling thread as inside a multi-threaded parallelChunks region while it lives.
class InsideChunks {
 public:
  InsideChunks() : before_(tInsideChunks) { tInsideChunks = true; }
  ~InsideChunks() { tInsideChunks = before_; }
  InsideChunks(const InsideChunks&) = delete;
  InsideChunks& operator=(const InsideChunks&) = delete;

 private:
  bool before_;
};

}  // namespace

bool insideParallelChunks() { return tInsideChunks; }

int threadSlot() { return tSlot; }

int threadCount() { return gThreads.load(std::memory_order_relaxed); }

void setThreadCount(int threads) { gThreads = std::max(1, std::min(kMaxThreads, threads)); }

void parallelChunks(size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& f) {
  parallelChunks(n, grain, f, nullptr);
}

void parallelChunks(size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& f,
                    const std::function<void()>& poll) {
  if (n == 0) return;
  if (grain == 0) grain = 1;
  const size_t chunks = chunkCount(n, grain);
  const size_t workers = std::min<size_t>(size_t(threadCount()), chunks);
  if (workers <= 1 || kSingleThreaded || tInsideChunks || nestedRunsSerially()) {
    for (size_t c = 0; c < chunks; ++c) f(c, c * grain, std::min(n, (c + 1) * grain));
    return;
  }
  std::atomic<size_t> next{0};
  std::mutex m;
  std::condition_variable finished;
  size_t running = workers - 1;
  size_t failedChunk = chunks;
  std::exception_ptr failure;
  auto work = [&] {
    const InsideChunks inside;
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
  for (size_t t = 1; t < workers; ++t) {
    pool.emplace_back([&] {
      const SlotHold slot;
      tWorker = true;
      work();
      std::lock_guard<std::mutex> lock(m);
      if (--running == 0) finished.notify_one();
    });
  }
  work();
  if (poll) {
    // The caller's chunks are done: it polls every 5 ms until the other threads finish.
    std::unique_lock<std::mutex> lock(m);
    while (running > 0) {
      if (finished.wait_for(lock, std::chrono::milliseconds(5), [&] { return running == 0; })) break;
      lock.unlock();
      poll();
      lock.lock();
    }
  }
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b) {
  if (threadCount() <= 1 || kSingleThreaded || tInsideChunks || nestedRunsSerially()) {
    a();
    b();
    return;
  }
  std::exception_ptr fb;
  std::thread t([&] {
    const SlotHold slot;
    tWorker = true;
    try {
      b();
    } catch (...) {
      fb = std::current_exception();
    }
  });
  std::exception_ptr fa;
  try {
    // a's own regions run on this thread while b's lives (the nesting rule): started
    // threads would be one more than threadCount(), and in the pthreads build one more
    // than its pool, which would wait forever for the caller's event loop.
    const InsideChunks inside;
    a();
  } catch (...) {
    fa = std::current_exception();
  }
  t.join();
  if (fa) std::rethrow_exception(fa);
  if (fb) std::rethrow_exception(fb);
}

}  // namespace anisomesh
