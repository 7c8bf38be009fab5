// Web Worker: all anisomesh work runs here so the page never freezes.
// Protocol: { id, op, args } in; { id, ok: true, result } or { id, ok: false, error: { code, message } } out.
import { loadAnisomesh } from '../wasm/browser.js';

const ready = loadAnisomesh();

const ops = {
  version: (am) => am.version,
  // Ellipses of two metrics and of their intersection, all centred at the origin.
  ellipses: (am, { a, b, segments = 128 }) => {
    const c = am.intersectMetrics(a, b);
    return {
      a: am.metricEllipse(a, [0, 0], segments),
      b: am.metricEllipse(b, [0, 0], segments),
      c: am.metricEllipse(c, [0, 0], segments),
      intersection: c,
    };
  },
};

self.onmessage = async (event) => {
  const { id, op, args } = event.data;
  try {
    const am = await ready;
    if (!(op in ops)) throw Object.assign(new Error(`unknown operation '${op}'`), { code: 'INVALID_ARGUMENT' });
    const result = ops[op](am, args ?? {});
    const transfer = result && typeof result === 'object'
      ? Object.values(result).filter((v) => ArrayBuffer.isView(v)).map((v) => v.buffer)
      : [];
    self.postMessage({ id, ok: true, result }, transfer);
  } catch (e) {
    self.postMessage({ id, ok: false, error: { code: e.code ?? 'INTERNAL', message: e.message } });
  }
};
