// Colour maps shared by the 3D views, the histograms and the legends.

function lerpStops(stops, t) {
  t = Math.min(1, Math.max(0, t));
  const x = t * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  const a = stops[i], b = stops[i + 1];
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

// Element quality 0 (bad) .. 1 (ideal): red -> orange -> yellow -> light green -> teal.
const qualityStops = [[0.70, 0.09, 0.17], [0.93, 0.42, 0.18], [0.98, 0.80, 0.33], [0.66, 0.85, 0.55], [0.36, 0.70, 0.75]];
export function qualityColor(q) {
  // Most elements sit in [0.7, 1]: stretch that range.
  return lerpStops(qualityStops, Math.pow(Math.max(0, q), 2.2));
}

// Metric edge length around the target 1: blue (short) .. grey (1) .. red (long), on log2 in [-1, 1].
const lengthStops = [[0.13, 0.32, 0.70], [0.45, 0.62, 0.85], [0.55, 0.55, 0.55], [0.90, 0.52, 0.40], [0.75, 0.12, 0.12]];
export function lengthColor(l) {
  return lerpStops(lengthStops, 0.5 + 0.5 * Math.log2(Math.max(l, 1e-6)));
}

// Requested size (control-space ellipses): purple (fine) .. red .. orange .. green .. blue (coarse),
// t in [0, 1]; every stop is dark enough to read on the light background.
const sizeStops = [[0.50, 0.05, 0.50], [0.80, 0.15, 0.15], [0.85, 0.50, 0.05], [0.15, 0.55, 0.25], [0.12, 0.32, 0.70]];
export function sizeColor(t) {
  return lerpStops(sizeStops, t);
}

// A field's value scaled to [0, 1] (adaptation mode): blue (low) .. white .. red (high).
const fieldStops = [[0.16, 0.30, 0.67], [0.55, 0.70, 0.88], [0.96, 0.96, 0.94], [0.93, 0.60, 0.45], [0.70, 0.13, 0.16]];
export function fieldColor(t) {
  return lerpStops(fieldStops, t);
}

export function css([r, g, b]) {
  return `rgb(${Math.round(r * 255)}, ${Math.round(g * 255)}, ${Math.round(b * 255)})`;
}
