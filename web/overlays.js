// What a metric source looks like in the 2D view, and how its handles move it.
// Pure geometry (no three.js) so it is easy to reason about and reuse.

const TAU = 2 * Math.PI;

function circle([cx, cy], r, n = 96) {
  const out = [];
  for (let k = 0; k <= n; k++) out.push([cx + r * Math.cos((k / n) * TAU), cy + r * Math.sin((k / n) * TAU)]);
  return out;
}

/** Unit ellipse of {alpha, h1, h2} scaled by s around c (h1 along alpha). */
export function ellipse([cx, cy], { alpha = 0, h1, h2 = h1 }, s = 1, n = 72) {
  const ca = Math.cos(alpha), sa = Math.sin(alpha);
  const out = [];
  for (let k = 0; k <= n; k++) {
    const t = (k / n) * TAU;
    const u = s * h1 * Math.cos(t), v = s * h2 * Math.sin(t);
    out.push([cx + u * ca - v * sa, cy + u * sa + v * ca]);
  }
  return out;
}

/** Magnification of a source's metric ellipse so it reads next to its radius (1 when already large). */
export function ellipseScale(metric, radius) {
  const h = Math.max(metric.h1, metric.h2 ?? metric.h1);
  return Math.max(1, (0.45 * radius) / h);
}

// Outline at distance r around the segment p1-p2 (a stadium).
function capsule(p1, p2, r, n = 48) {
  const dx = p2[0] - p1[0], dy = p2[1] - p1[1];
  const a = Math.atan2(dy, dx);
  const out = [];
  for (let k = 0; k <= n; k++) {
    const t = a + Math.PI / 2 + (k / n) * Math.PI;
    out.push([p1[0] + r * Math.cos(t), p1[1] + r * Math.sin(t)]);
  }
  for (let k = 0; k <= n; k++) {
    const t = a - Math.PI / 2 + (k / n) * Math.PI;
    out.push([p2[0] + r * Math.cos(t), p2[1] + r * Math.sin(t)]);
  }
  out.push(out[0]);
  return out;
}

const mid = (p, q) => [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2];

// Lines parallel to p1-p2 at signed distance d, extended by the same length on each side.
function offsetLine(p1, p2, d) {
  const dx = p2[0] - p1[0], dy = p2[1] - p1[1];
  const l = Math.hypot(dx, dy) || 1;
  const nx = -dy / l, ny = dx / l;
  return [[p1[0] + nx * d, p1[1] + ny * d], [p2[0] + nx * d, p2[1] + ny * d]];
}

/**
 * Drawing of a source: { lines: [{ points: [[x, y]...], kind: 'shape'|'ellipse'|'guide' }], handles: [{ key, p }] }.
 * Handle keys name the point they move: 'center', 'p1', 'p2', or 'mid' (moves p1 and p2 together).
 */
export function sourceOverlay(s) {
  const lines = [], handles = [];
  if (s.type === 'radial') {
    lines.push({ points: circle(s.center, s.radius), kind: 'shape' });
    lines.push({ points: ellipse(s.center, s.metric, ellipseScale(s.metric, s.radius)), kind: 'ellipse' });
    handles.push({ key: 'center', p: s.center });
  } else if (s.type === 'segment') {
    lines.push({ points: [s.p1, s.p2], kind: 'guide' });
    lines.push({ points: capsule(s.p1, s.p2, s.radius), kind: 'shape' });
    lines.push({ points: ellipse(mid(s.p1, s.p2), s.metric, ellipseScale(s.metric, s.radius)), kind: 'ellipse' });
    handles.push({ key: 'p1', p: s.p1 }, { key: 'p2', p: s.p2 }, { key: 'mid', p: mid(s.p1, s.p2) });
  } else if (s.type === 'analytic' && s.field === 'point') {
    // Where the size has doubled and grown tenfold: h0 + growth d = 2 h0, 10 h0.
    if (s.growth > 0) {
      lines.push({ points: circle(s.center, s.h0 / s.growth), kind: 'guide' });
      lines.push({ points: circle(s.center, (9 * s.h0) / s.growth), kind: 'guide' });
    }
    handles.push({ key: 'center', p: s.center });
  } else if (s.type === 'analytic' && s.field === 'shear_layer_circle') {
    lines.push({ points: circle(s.center, s.radius), kind: 'shape' });
    lines.push({ points: circle(s.center, s.radius + s.thickness), kind: 'guide' });
    if (s.radius > s.thickness) lines.push({ points: circle(s.center, s.radius - s.thickness), kind: 'guide' });
    handles.push({ key: 'center', p: s.center });
  } else if (s.type === 'analytic' && s.field === 'boundary_layer') {
    lines.push({ points: [s.p1, s.p2], kind: 'shape' });
    lines.push({ points: offsetLine(s.p1, s.p2, s.thickness), kind: 'guide' });
    lines.push({ points: offsetLine(s.p1, s.p2, -s.thickness), kind: 'guide' });
    handles.push({ key: 'p1', p: s.p1 }, { key: 'p2', p: s.p2 }, { key: 'mid', p: mid(s.p1, s.p2) });
  }
  return { lines, handles };
}

/** Moves the handle `key` of source s to p (mutates s). `from` is where the drag started (for 'mid'). */
export function moveHandle(s, key, p, from) {
  const r = (x) => Math.round(x * 1e6) / 1e6;  // keeps the JSON (and the URL) short
  const q = [r(p[0]), r(p[1])];
  if (key === 'center') s.center = q;
  else if (key === 'p1') s.p1 = q;
  else if (key === 'p2') s.p2 = q;
  else if (key === 'mid') {
    const dx = p[0] - from.p[0], dy = p[1] - from.p[1];
    s.p1 = [r(from.p1[0] + dx), r(from.p1[1] + dy)];
    s.p2 = [r(from.p2[0] + dx), r(from.p2[1] + dy)];
  }
}
