#pragma once
// A small fork-join layer over std::thread for the stages that parallelise (reading,
// control-space evaluation, the quality report, writing). Work is cut into chunks whose
// boundaries depend on the work size only, never on the number of threads, and results
// are combined in chunk order: the output is the same for any thread count.
//
// Why std::thread and not oneTBB: the parallel stages are a handful of flat loops run once
// per stage (thread start-up, ~50 us, is noise against them), the WebAssembly build must
// compile the same sources without threads, and a dependency would have to be built for
// both targets. The default WebAssembly build runs on one thread; the opt-in pthreads build
// (wasm/dist/anisomesh-core-mt) on up to 8 (the caller and its worker pool, which the
// bindings clamp to), nested calls from its workers on the worker itself.
#include <cstddef>
#include <functional>

namespace anisomesh {

// Worker threads used by parallelChunks / parallelInvoke (process-wide; default 1).
int threadCount();
// Sets the worker threads, clamped to [1, 256] (1 in the WebAssembly build, 8 with pthreads).
void setThreadCount(int threads);

// Calls f(chunk, begin, end) for the chunks [k * grain, min(n, (k + 1) * grain)) of [0, n),
// on up to threadCount() threads. f must only write what its chunk owns. If calls throw,
// the exception of the lowest chunk is rethrown after every thread has finished.
void parallelChunks(size_t n, size_t grain, const std::function<void(size_t chunk, size_t begin, size_t end)>& f);

// As above, and poll() runs on the calling thread every 5 ms once it has no chunk left and
// waits for the other threads: progress reports of the work in flight from the calling
// thread only (never from another). poll must not throw.
void parallelChunks(size_t n, size_t grain, const std::function<void(size_t chunk, size_t begin, size_t end)>& f,
                    const std::function<void()>& poll);

// Number of chunks parallelChunks cuts [0, n) into.
inline size_t chunkCount(size_t n, size_t grain) { return grain == 0 ? 0 : (n + grain - 1) / grain; }

// Runs a and b, concurrently when threadCount() > 1; rethrows a's exception first.
void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b);

// Called inside a parallelChunks region that runs on several threads, parallelChunks and
// parallelInvoke run on the calling thread (the outer loop already keeps the threads busy;
// nesting would start threads^2 of them).
bool insideParallelChunks();

// Slots: every thread the layer starts holds a slot number no other live thread holds
// (threads it did not start hold 0), so per-thread tallies indexed by it need no atomics.
constexpr int kThreadSlots = 512;
// The calling thread's slot, in [0, kThreadSlots).
int threadSlot();

}  // namespace anisomesh
