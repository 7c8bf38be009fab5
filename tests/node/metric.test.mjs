// The metric slice through the package, imported by its name as a user would.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const close = (a, b, tol = 1e-9) => Math.abs(a - b) <= tol * Math.max(1, Math.abs(a), Math.abs(b));

test('loadAnisomesh returns one cached instance with a version', async () => {
  assert.equal(await loadAnisomesh(), am);
  // The core's version is package.json's (written in one place).
  const pkg = JSON.parse(readFileSync(new URL('../../package.json', import.meta.url), 'utf8'));
  assert.equal(am.version, pkg.version);
});

test('metric from sizes: tensor, transformation matrix and sizes agree', () => {
  const m = am.metric({ alpha: 0.3, h1: 0.01, h2: 2 });
  // M = Mt Mt^T with Mt symmetric.
  assert.ok(close(m.m11, m.t11 * m.t11 + m.t12 * m.t12));
  assert.ok(close(m.m12, m.t11 * m.t12 + m.t12 * m.t22));
  assert.ok(close(m.m22, m.t12 * m.t12 + m.t22 * m.t22));
  assert.ok(close(m.h1, 0.01) && close(m.h2, 2));
  // Length 1 along the h1 direction at size h1.
  assert.ok(close(am.metricLength(m, [0.01 * Math.cos(0.3), 0.01 * Math.sin(0.3)]), 1));
  // The same metric from its tensor.
  const back = am.metric({ m11: m.m11, m12: m.m12, m22: m.m22 });
  assert.ok(close(back.h1, 0.01, 1e-6) && close(back.h2, 2, 1e-6));
});

test('intersection of crossed stretches is the isotropic fine metric', () => {
  const c = am.intersectMetrics({ alpha: 0, h1: 0.1, h2: 1 }, { alpha: Math.PI / 2, h1: 0.1, h2: 1 });
  assert.ok(close(c.h1, 0.1) && close(c.h2, 0.1));
});

test('intersection lies inside both unit ellipses (random metrics)', () => {
  let seed = 12345;
  const rnd = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let trial = 0; trial < 200; trial++) {
    const a = { alpha: 6 * rnd() - 3, h1: 0.01 + rnd(), h2: 0.01 + rnd() };
    const b = { alpha: 6 * rnd() - 3, h1: 0.01 + rnd(), h2: 0.01 + rnd() };
    const c = am.intersectMetrics(a, b);
    for (let k = 0; k < 32; k++) {
      const v = [Math.cos((Math.PI * k) / 32), Math.sin((Math.PI * k) / 32)];
      // Longer in the metric means a smaller requested size.
      assert.ok(am.metricLength(c, v) >= am.metricLength(a, v) * (1 - 1e-9));
      assert.ok(am.metricLength(c, v) >= am.metricLength(b, v) * (1 - 1e-9));
    }
  }
});

test('interpolation acts on the transformation matrix', () => {
  const a = { h: 1 }, b = { alpha: 0, h1: 0.5, h2: 0.25 };
  const mid = am.interpolateMetrics(a, b, 0.5);
  const A = am.metric(a), B = am.metric(b);
  assert.ok(close(mid.t11, (A.t11 + B.t11) / 2) && close(mid.t22, (A.t22 + B.t22) / 2));
  assert.ok(close(am.metricDifference(a, a), 0, 1e-12));
});

test('ellipse points have metric length 1 from the centre', () => {
  const m = { alpha: 0.7, h1: 0.2, h2: 0.05 };
  const pts = am.metricEllipse(m, [3, -1], 16);
  assert.ok(pts instanceof Float64Array);
  assert.equal(pts.length, 32);
  for (let i = 0; i < 16; i++) assert.ok(close(am.metricLength(m, [pts[2 * i] - 3, pts[2 * i + 1] + 1]), 1, 1e-9));
});

test('bad metrics throw AnisomeshError with a code, and the module keeps working', () => {
  const cases = [
    [{ h1: NaN, h2: 1 }, 'INVALID_METRIC', /h1/],
    [{ h1: 1, h2: 0 }, 'INVALID_METRIC', /h2/],
    [{ h1: -1, h2: 1 }, 'INVALID_METRIC', /h1/],
    [{ h: Infinity }, 'INVALID_METRIC', /h must be finite/],
    [{ m11: 1, m12: 2, m22: 1 }, 'INVALID_METRIC', /positive definite/],
    [{ h1: '1', h2: 1 }, 'INVALID_ARGUMENT', /metric\.h1/],
    [{}, 'INVALID_ARGUMENT', /metric needs/],
    [null, 'INVALID_ARGUMENT', /expected a metric/],
  ];
  for (const [spec, code, message] of cases) {
    assert.throws(() => am.metric(spec), (e) => {
      assert.ok(e instanceof AnisomeshError && e instanceof Error, `not an AnisomeshError: ${e}`);
      assert.equal(e.name, 'AnisomeshError');
      assert.equal(e.code, code, `${JSON.stringify(spec)}: ${e.message}`);
      assert.match(e.message, message);
      return true;
    });
    // Still usable after every error.
    assert.ok(close(am.metric({ h: 2 }).h1, 2));
  }
  assert.throws(() => am.interpolateMetrics({ h: 1 }, { h: 2 }, 1.5), { code: 'INVALID_ARGUMENT' });
  assert.throws(() => am.metricEllipse({ h: 1 }, [0, 0], 2), { code: 'INVALID_ARGUMENT' });
  assert.throws(() => am.metricLength({ h: 1 }, [1]), { code: 'INVALID_ARGUMENT', message: /v: expected \[x, y\]/ });
});
