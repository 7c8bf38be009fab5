// App state (the case being edited + view settings), its URL form, and the checks the
// core does not make itself (so that an error can point at the control that caused it).

/** View settings kept in the URL next to the case. */
export const defaultView = () => ({
  view: 'split',            // '2d' | '3d' | 'split'
  colorBy: 'quality',       // 'quality' | 'field' (adaptation mode) | 'none'
  edges: 'length',          // 'length' (metric length colours) | 'plain' | 'off'
  controlSpace: false,      // control-space overlay (structure + ellipses at nodes)
  sources: true,            // source handles, ellipses and radii
  lift: 0,                  // 3D view of a planar mesh: height = lift * log10(hmax / h) (0 = flat)
  expression: '',           // analytic size expression h(u, v) (see app.js: not in the case format yet)
});

// --- URL hash: deflate-raw + base64url of the JSON state --------------------------------

function toBase64Url(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64Url(text) {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

async function pipe(bytes, stream) {
  const r = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await r.arrayBuffer());
}

/** '#s=...' for a state object (compressed so a whole case fits in a shareable link). */
export async function encodeState(state) {
  const json = new TextEncoder().encode(JSON.stringify(state));
  return `#s=${toBase64Url(await pipe(json, new CompressionStream('deflate-raw')))}`;
}

/** The state in a location hash, or null when there is none; throws on a damaged hash. */
export async function decodeState(hash) {
  const m = /^#s=([A-Za-z0-9_-]+)$/.exec(hash ?? '');
  if (!m) return null;
  const bytes = await pipe(fromBase64Url(m[1]), new DecompressionStream('deflate-raw'));
  return JSON.parse(new TextDecoder().decode(bytes));
}

// --- checks before a case goes to the core ---------------------------------------------

/** An input error tied to a place in the UI: target is e.g. 'sources[1].radius', 'domain', 'maxElements'. */
export class InputError extends Error {
  constructor(target, message, code = 'INVALID_ARGUMENT') {
    super(message);
    this.target = target;
    this.code = code;
  }
}

/** Checks the core accepts silently but that make no sense to a user (e.g. a zero radius). */
export function checkCase(c) {
  (c.sources ?? []).forEach((s, i) => {
    if ((s.type === 'radial' || s.type === 'segment') && !(s.radius > 0)) {
      throw new InputError(`sources[${i}].radius`, `sources[${i}].radius: must be positive, got ${s.radius} (a source with zero radius acts nowhere)`);
    }
  });
}

/** Where in the UI a core error belongs, from its code and the JSON path in its message. */
export function errorTarget(code, message) {
  const src = /sources\[(\d+)\](?:\.([A-Za-z0-9_.]+))?/.exec(message);
  if (src) return `sources[${src[1]}]${src[2] ? `.${src[2]}` : ''}`;
  if (code === 'ELEMENT_BUDGET_EXCEEDED' || /maxElements/.test(message)) return 'maxElements';
  const sm = /(?:^|[^.\w])metric\.(\w+)/.exec(message);
  if (sm) return `metric.${sm[1]}`;  // surface cases: chordTolerance, hmin, hmax, maxAspectRatio, gradation
  const smText = /^metric: .*?\b(chordTolerance|hmin|hmax|maxAspectRatio|gradation)\b/.exec(message);
  if (smText) return `metric.${smText[1]}`;
  const cs = /controlSpace\.(\w+)/.exec(message);
  if (cs) return cs[1];  // hmin, hmax, gradation, kind, interpolation
  if (/^(OPEN_CONTOUR|SELF_INTERSECTING_CONTOUR|HOLE_OUTSIDE_DOMAIN|ZERO_LENGTH_CURVE|INVALID_DOMAIN)$/.test(code) || /domain/.test(message)) return 'domain';
  return 'case';
}
