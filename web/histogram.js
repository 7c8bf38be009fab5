// Histograms drawn on a 2D canvas (metric edge length, element quality).

/** Counts of values in `bins` equal bins over [lo, hi]; values outside go to the end bins. */
export function binValues(values, lo, hi, bins) {
  const counts = new Uint32Array(bins);
  const scale = bins / (hi - lo);
  for (let i = 0; i < values.length; i++) {
    const b = Math.floor((values[i] - lo) * scale);
    counts[b < 0 ? 0 : b >= bins ? bins - 1 : b]++;
  }
  return counts;
}

/**
 * Draws a histogram.
 * opts: { lo, hi, bins, title, color(x) -> css colour for a bin centre, band: [a, b] shaded target
 *         range, ticks: [x...], marker: x (e.g. the mean) }
 */
export function drawHistogram(canvas, values, opts) {
  const { lo, hi, bins, title, color = () => '#4a78b5', band = null, ticks = [], marker = null } = opts;
  const dpr = window.devicePixelRatio || 1;
  const cssW = canvas.clientWidth || 280, cssH = canvas.clientHeight || 110;
  if (canvas.width !== Math.round(cssW * dpr) || canvas.height !== Math.round(cssH * dpr)) {
    canvas.width = Math.round(cssW * dpr);
    canvas.height = Math.round(cssH * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, cssW, cssH);
  const pad = { l: 6, r: 6, t: 16, b: 16 };
  const w = cssW - pad.l - pad.r, h = cssH - pad.t - pad.b;
  const X = (x) => pad.l + ((x - lo) / (hi - lo)) * w;

  ctx.font = '11px system-ui, sans-serif';
  ctx.fillStyle = '#333';
  ctx.textBaseline = 'top';
  ctx.textAlign = 'left';  // the context keeps its state between draws
  ctx.fillText(title, pad.l, 1);
  if (!values || values.length === 0) {
    ctx.fillStyle = '#999';
    ctx.fillText('no data', pad.l, pad.t + h / 2 - 6);
    return null;
  }
  const counts = binValues(values, lo, hi, bins);
  const max = Math.max(1, ...counts);
  ctx.textAlign = 'right';
  ctx.fillStyle = '#777';
  ctx.fillText(`n = ${values.length}`, cssW - pad.r, 1);
  ctx.textAlign = 'left';

  if (band) {
    ctx.fillStyle = 'rgba(40, 160, 80, 0.12)';
    ctx.fillRect(X(band[0]), pad.t, X(band[1]) - X(band[0]), h);
  }
  const bw = w / bins;
  for (let i = 0; i < bins; i++) {
    if (!counts[i]) continue;
    // sqrt scale keeps the tails visible next to the peak.
    const bh = Math.max(1, Math.sqrt(counts[i] / max) * h);
    ctx.fillStyle = color(lo + (i + 0.5) * (hi - lo) / bins);
    ctx.fillRect(pad.l + i * bw + 0.5, pad.t + h - bh, Math.max(1, bw - 1), bh);
  }
  ctx.strokeStyle = '#999';
  ctx.beginPath();
  ctx.moveTo(pad.l, pad.t + h + 0.5);
  ctx.lineTo(pad.l + w, pad.t + h + 0.5);
  ctx.stroke();
  ctx.fillStyle = '#555';
  ctx.textAlign = 'center';
  for (const t of ticks) {
    ctx.fillRect(X(t) - 0.5, pad.t + h, 1, 3);
    ctx.fillText(String(t), Math.min(Math.max(X(t), pad.l + 8), pad.l + w - 8), pad.t + h + 3);
  }
  if (marker !== null && Number.isFinite(marker)) {
    ctx.strokeStyle = '#c0392b';
    ctx.setLineDash([3, 2]);
    ctx.beginPath();
    ctx.moveTo(X(marker) + 0.5, pad.t);
    ctx.lineTo(X(marker) + 0.5, pad.t + h);
    ctx.stroke();
    ctx.setLineDash([]);
  }
  return counts;
}
