// Worker client: jobs with ids, progress messages, and cancellation by replacing the worker.
//
// The wasm core cannot be interrupted from JS (it is synchronous inside the worker), so a
// job that is still running when a newer one arrives is cancelled by terminating the
// worker and starting a fresh one. The page compiles the wasm once and posts the
// WebAssembly.Module to each new worker, so a restart costs an instantiation only.

const workerUrl = new URL('./worker.js', import.meta.url);
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

/**
 * One worker running jobs one at a time.
 * supersede: a new job cancels the queued and running ones (meshing); otherwise jobs queue (exports).
 */
export class JobRunner {
  constructor({ supersede = false, precompiled = true, onBusy = () => {}, onProgress = () => {} } = {}) {
    this.supersede = supersede;
    this.precompiled = precompiled;  // false: each worker fetches and compiles the wasm itself (for comparison)
    this.onBusy = onBusy;
    this.onProgress = onProgress;
    this.pending = new Map();  // id -> { resolve, reject, op, started }
    this.nextId = 1;
    this.restarts = 0;
    this.lastStartMs = null;   // time from creating a worker to its 'ready' message
    this.version = null;
    this.#start();
  }

  #start() {
    const t0 = performance.now();
    const worker = new Worker(workerUrl, { type: 'module' });
    this.worker = worker;
    this.ready = new Promise((resolve, reject) => {
      worker.onmessage = ({ data }) => {
        if (worker !== this.worker) return;  // a terminated worker's late message
        if (data.type === 'ready') {
          this.lastStartMs = performance.now() - t0;
          this.version = data.version;
          resolve(data.version);
        } else if (data.type === 'fatal') {
          reject(new Error(data.message));
        } else if (data.type === 'progress') {
          const p = this.pending.get(data.id);
          if (p) this.onProgress({ id: data.id, op: p.op, stage: data.stage, elapsedMs: performance.now() - p.started });
        } else if (data.type === 'result') {
          const p = this.pending.get(data.id);
          if (!p) return;
          this.pending.delete(data.id);
          this.#busyChanged();
          if (data.ok) p.resolve({ result: data.result, workerMs: data.workerMs, totalMs: performance.now() - p.started });
          else p.reject(Object.assign(new Error(data.error.message), { code: data.error.code }));
        }
      };
      worker.onerror = (e) => reject(new Error(e.message || 'worker failed to start'));
    });
    if (!this.precompiled) worker.postMessage({ type: 'init' });
    else {
      compileCore().then(
        (module) => worker.postMessage({ type: 'init', module }),
        () => worker.postMessage({ type: 'init' }),  // no precompiled module: the worker fetches itself
      );
    }
  }

  #busyChanged() { this.onBusy(this.pending.size > 0); }

  get busy() { return this.pending.size > 0; }

  /** Runs op in the worker; resolves to { result, workerMs, totalMs } or rejects (CancelledError when superseded). */
  run(op, args) {
    if (this.supersede && this.pending.size > 0) this.cancelAll();
    const id = this.nextId++;
    const promise = new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, op, started: performance.now() });
    });
    this.#busyChanged();
    this.worker.postMessage({ type: 'job', id, op, args });
    return promise;
  }

  /** Cancels every pending job: the worker is replaced by a fresh one. */
  cancelAll() {
    if (this.pending.size === 0) return;
    this.worker.terminate();
    this.restarts++;
    for (const p of this.pending.values()) p.reject(new CancelledError());
    this.pending.clear();
    this.#start();
    this.#busyChanged();
  }
}
