#pragma once
// Progress of tasks run concurrently (parallel.h), reported from the calling thread only: a
// callback bound to its thread (a JS function in the pthreads wasm build) stays there.
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace anisomesh {

class CallerProgress {
 public:
  // n tasks; report(offset + scale * mean of the tasks' fractions) answers false to cancel.
  // Made on the thread that will call parallelChunks.
  CallerProgress(size_t n, std::function<bool(double)> report, double offset = 0.0, double scale = 1.0);
  // The callback of task k (any thread): keeps its fraction; on the calling thread reports
  // the whole; false once any report answered false (every task stops at its next tick).
  std::function<bool(double)> task(size_t k);
  // For parallelChunks' poll (the calling thread, once its own tasks are done).
  std::function<void()> poll();

 private:
  void report();
  std::vector<std::atomic<double>> fraction_;
  std::atomic<bool> stop_{false};
  std::thread::id caller_;
  std::function<bool(double)> report_;
  double offset_, scale_;
};

}  // namespace anisomesh
