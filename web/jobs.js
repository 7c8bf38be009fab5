// Worker client: jobs with ids, progress messages, and cancellation.
//
// The wasm core is synchronous inside the worker, so a job still running when a newer one
// arrives is cancelled in one of two ways:
// - cooperatively, on a cross-origin isolated page (SharedArrayBuffer): the runner raises a
//   flag shared with the worker, whose progress callback tells the core to stop (it throws
//   CANCELLED within a progress step, a few ms); the worker, its instance and the core's
//   caches (a surface's curvature stages) stay, so nothing is started or warmed again;
// - otherwise (and for jobs without progress, such as a report) by terminating the worker.
//   The page compiles the wasm once and posts the WebAssembly.Module to each new worker, and
//   a superseding runner keeps a spare worker instantiated ahead of time: a cancellation
//   swaps the spare in at once, so the new job does not wait for a start-up.

const workerUrl = new URL('./worker.js', import.meta.url);
// Threads of each worker's core. ?threads=2 on a cross-origin isolated page: the worker loads
// the pthreads build ('anisomesh/threads'), its parallel stages on 2 threads. Default 1 (the
// single-threaded build): on the page, surface drags were no faster with it (software WebGL
// takes the second core, and the pthreads build's JS exceptions cost 5-13 %; docs/SCALING.md).
const coreThreads = globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function'
  ? Math.max(1, Math.min(2, Number(new URLSearchParams(globalThis.location?.search ?? '').get('threads') ?? 1) || 1))
  : 1;
const wasmUrl = new URL('../wasm/dist/anisomesh-core.wasm', import.meta.url);

let compiled = null;
/** The wasm core compiled once per page (streaming compile while it downloads). */
export function compileCore() {
  if (!compiled) {
    compiled = (WebAssembly.compileStreaming
      ? WebAssembly.compileStreaming(fetch(wasmUrl))
      : fetch(wasmUrl).then((r) => r.arrayBuffer()).then((b) => WebAssembly.compile(b)));
  }
  return compiled;
}

export class CancelledError extends Error {
  constructor() {
    super('superseded by a newer job');
    this.name = 'CancelledError';
    this.code = 'CANCELLED';
  }
}

/** Wall-clock milliseconds comparable between the page and its workers (their performance.now() origins differ). */
export const wallNow = () => performance.timeOrigin + performance.now();

/**
 * One worker running jobs one at a time.
 * supersede: a new job cancels the queued and running ones (meshing), and a spare worker
 * is kept ready to take over; otherwise jobs queue (exports).
 */
export class JobRunner {
  constructor({ supersede = false, precompiled = true, spare = supersede, onBusy = () => {}, onProgress = () => {} } = {}) {
    this.supersede = supersede;
    this.precompiled = precompiled;  // false: each worker fetches and compiles the wasm itself (for comparison)
    this.useSpare = spare;
    this.onBusy = onBusy;
    this.onProgress = onProgress;
    this.pending = new Map();  // id -> { resolve, reject, op, started }
    this.nextId = 1;
    this.restarts = 0;         // cancellations that terminated the worker
    this.cancellations = 0;    // all cancellations (cooperative ones keep the worker)
    this.stoppedInWorker = 0;  // cancelled jobs the core stopped (their late CANCELLED results)
    // A flag shared with each worker: jobs with ids below its value are cancelled.
    this.cooperative = supersede && globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function';
    this.spareSwaps = 0;       // cancellations served by the spare worker (no start-up wait)
    this.lastStartMs = null;   // time from creating a worker to its 'ready' message
    this.version = null;
    this.spare = null;
    this.spareWanted = false;  // a cancellation's spare, started after the next result
    this.lastWarm = null;      // [key, op, args] of the last warmSpare() call
    this.#use(this.#spawn());
    if (this.useSpare) this.spare = this.#spawn();
  }

  /** A new worker slot: { worker, ready (promise of the version), isReady }. */
  #spawn() {
    const t0 = performance.now();
    const worker = new Worker(workerUrl, { type: 'module' });
    const slot = { worker, isReady: false, startMs: null, cancelFlag: null };
    if (this.cooperative) slot.cancelFlag = new Int32Array(new SharedArrayBuffer(4));
    const cancelFlag = slot.cancelFlag;
    slot.ready = new Promise((resolve, reject) => {
      worker.onmessage = ({ data }) => {
        if (data.type === 'ready') {
          slot.isReady = true;
          slot.startMs = performance.now() - t0;
          this.version = data.version;
          this.threads = data.threads ?? 1;  // the core's threads in this worker
          resolve(data.version);
        } else if (data.type === 'fatal') {
          reject(new Error(data.message));
        } else if (slot === this.slot) {
          this.#message(data);
        }  // else: a terminated worker's late message
      };
      worker.onerror = (e) => reject(new Error(e.message || 'worker failed to start'));
    });
    slot.ready.catch(() => {});  // reported through this.ready when the slot is in use
    if (!this.precompiled || coreThreads > 1) worker.postMessage({ type: 'init', cancelFlag, threads: coreThreads });
    else {
      compileCore().then(
        (module) => worker.postMessage({ type: 'init', module, cancelFlag }),
        () => worker.postMessage({ type: 'init', cancelFlag }),  // no precompiled module: the worker fetches itself
      );
    }
    return slot;
  }

  #use(slot) {
    this.slot = slot;
    this.worker = slot.worker;
    this.ready = slot.ready.then((v) => {
      if (this.slot === slot) this.lastStartMs = slot.startMs;
      return v;
    });
  }

  #message(data) {
    const p = this.pending.get(data.id);
    if (!p) {
      if (data.type === 'result' && !data.ok && data.error?.code === 'CANCELLED') this.stoppedInWorker++;
      return;
    }
    if (data.type === 'progress') {
      this.onProgress({ id: data.id, op: p.op, stage: data.stage, fraction: data.fraction ?? null, elapsedMs: performance.now() - p.started });
    } else if (data.type === 'result') {
      this.pending.delete(data.id);
      this.#busyChanged();
      // The first result after a cancellation: the used-up spare is replaced a task later
      // (once the result's handlers have drawn it).
      if (this.spareWanted) setTimeout(() => this.#replaceSpare(), 0);
      if (data.ok) p.resolve({ result: data.result, workerMs: data.workerMs, marks: data.marks, totalMs: performance.now() - p.started, receivedAt: wallNow() });
      else p.reject(Object.assign(new Error(data.error.message), { code: data.error.code }));
    }
  }

  #busyChanged() { this.onBusy(this.pending.size > 0); }

  get busy() { return this.pending.size > 0; }

  /**
   * Runs op in the worker; resolves to { id, result, workerMs, marks, totalMs, receivedAt }
   * or rejects (CancelledError when superseded). marks: the worker's wall-clock times of
   * the job's steps (posted, received, ready, and what the op adds).
   */
  run(op, args) {
    if (this.supersede && this.pending.size > 0) this.cancelAll();
    const id = this.nextId++;
    const promise = new Promise((resolve, reject) => {
      this.pending.set(id, { resolve: (r) => resolve({ id, ...r }), reject, op, started: performance.now() });
    });
    this.#busyChanged();
    this.worker.postMessage({ type: 'job', id, op, args, postedAt: wallNow() });
    return promise;
  }

  /**
   * Runs op in the spare worker for its side effects (the core's caches), once per key and
   * spare: a cancellation swaps in a worker that has already done that work. The result is
   * dropped (ids 0 match no pending job). Returns whether a job was posted.
   */
  warmSpare(key, op, args) {
    this.lastWarm = [key, op, args];
    return Boolean(this.spare) && JobRunner.#warmSlot(this.spare, key, op, args);
  }

  /** Posts op to slot's worker once per key (id 0: its result matches no pending job). */
  static #warmSlot(slot, key, op, args) {
    if (slot.warmKey === key) return false;
    slot.warmKey = key;
    slot.worker.postMessage({ type: 'job', id: 0, op, args, postedAt: wallNow() });
    return true;
  }

  /**
   * Runs op in this runner's own worker for its side effects, once per key and worker (as
   * warmSpare() does for the spare): a second mesh lane (see app.js) must hold the case's
   * curvature stages before it takes a drag's input. Returns whether a job was posted.
   */
  warm(key, op, args) { return JobRunner.#warmSlot(this.slot, key, op, args); }

  /** Whether this runner's worker is started and was warmed for key (see warm()). */
  warmFor(key) { return this.slot.isReady && this.slot.warmKey === key; }

  /** Whether every pending job can be cancelled without terminating the worker. */
  get cancelsInWorker() {
    return Boolean(this.slot.cancelFlag) && [...this.pending.values()].every((p) => p.op === 'mesh');
  }

  /**
   * Cancels every pending job: cooperatively when every one reports progress (meshing) on an
   * isolated page, else the worker is replaced by the spare (or a fresh one).
   */
  cancelAll() {
    if (this.pending.size === 0) return;
    this.cancellations++;
    if (this.cancelsInWorker) {
      // The running job stops at its next progress step and the queued ones are skipped; their
      // late messages match no pending job. The next job queues behind them in this worker.
      Atomics.store(this.slot.cancelFlag, 0, this.nextId);
      for (const p of this.pending.values()) p.reject(new CancelledError());
      this.pending.clear();
      this.#busyChanged();
      return;
    }
    this.worker.terminate();
    this.restarts++;
    for (const p of this.pending.values()) p.reject(new CancelledError());
    this.pending.clear();
    const spare = this.spare;
    this.spare = null;
    if (spare?.isReady) this.spareSwaps++;
    this.#use(spare ?? this.#spawn());
    // The next spare starts once the job that follows the cancellation has delivered: its
    // start-up (module glue, instance, bindings) would take CPU from the job the user waits
    // for (a drag's release); a second cancellation before then starts a fresh worker.
    if (this.useSpare) this.spareWanted = true;
    this.#busyChanged();
  }

  /** The spare a cancellation used up, replaced (see cancelAll). */
  #replaceSpare() {
    if (!this.spareWanted) return;
    this.spareWanted = false;
    this.spare = this.#spawn();
    // The warm-up the used spare had (or was asked for last).
    if (this.lastWarm) this.warmSpare(...this.lastWarm);
  }
}
