// Every documented error code (wasm/index.d.ts) is produced through the package, with a
// message naming the problem, and the module keeps working after each.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const line = (p1, p2) => ({ type: 'line', p1, p2 });
const square = [line([0, 0], [1, 0]), line([1, 0], [1, 1]), line([1, 1], [0, 1]), line([0, 1], [0, 0])];
const planar = (domain, extra = {}) => ({ domain, controlSpace: { hmax: 0.1 }, ...extra });
// A one-patch surface case on the expression surface z(u, v) over [0, 1]^2, trimmed by outer.
const surfaceCase = (z, outer) => ({
  metric: { chordTolerance: 0.01, hmin: 0.01, hmax: 0.2 },
  patches: [{ name: 'p', surface: { type: 'expression', x: 'u', y: 'v', z, domain: [[0, 0], [1, 1]] }, outer }],
});

const cases = {
  INVALID_ARGUMENT: () => am.metricEllipse({ h: 1 }, [0, 0], 1),
  INVALID_METRIC: () => am.metric({ m11: 1, m12: 2, m22: 1 }),
  OPEN_CONTOUR: () => am.meshCase(planar({ outer: square.slice(0, 3) })),
  SELF_INTERSECTING_CONTOUR: () => am.meshCase(planar({
    outer: [line([0, 0], [1, 1]), line([1, 1], [1, 0]), line([1, 0], [0, 1]), line([0, 1], [0, 0])],
  })),
  HOLE_OUTSIDE_DOMAIN: () => am.meshCase(planar({ outer: square, holes: [[{ type: 'circle', center: [3, 3], radius: 0.2 }]] })),
  ZERO_LENGTH_CURVE: () => am.meshCase(planar({ outer: [...square.slice(0, 2), line([1, 1], [1, 1]), ...square.slice(2)] })),
  // A trimming contour reaching outside the patch's parameter domain.
  INVALID_DOMAIN: () => am.meshCase(surfaceCase('0', [line([0, 0], [2, 0]), line([2, 0], [2, 1]), line([2, 1], [0, 1]), line([0, 1], [0, 0])])),
  // A surface expression that is NaN on the patch.
  INVALID_SURFACE: () => am.meshCase(surfaceCase('sqrt(u - 10)', square)),
  ELEMENT_BUDGET_EXCEEDED: () => am.meshCase(planar({ outer: square }), { maxElements: 10 }),
  PARSE_ERROR: () => am.meshCase('{"domain": '),
  CANCELLED: () => am.meshCase(planar({ outer: square }, { controlSpace: { hmax: 0.01 } }), { onProgress: () => false }),
};

for (const [code, fn] of Object.entries(cases)) {
  test(`${code} is produced with a message`, () => {
    assert.throws(fn, (e) => {
      assert.ok(e instanceof AnisomeshError, `${code}: got ${e}`);
      assert.equal(e.code, code, e.message);
      assert.ok(e.message.length > 10, e.message);
      return true;
    });
    assert.ok(am.meshCase(planar({ outer: square })).mesh.triangles.length > 0, 'the module keeps working');
  });
}

test('IO_ERROR and INTERNAL are documented for file access (the Node CLI, tests/node/cli.test.mjs) and core bugs', () => {
  // The package itself reads no files: IO_ERROR comes from `npx anisomesh` (tested there);
  // INTERNAL marks a broken invariant of the core and has no input that produces it on purpose.
  const dts = readFileSync(new URL('../../wasm/index.d.ts', import.meta.url), 'utf8');
  const documented = [...dts.matchAll(/\| '([A-Z_]+)'/g)].map((m) => m[1]);
  // WASM_LOAD_FAILED is thrown by loadAnisomesh() itself (tests/node/load.test.mjs);
  // OUT_OF_MEMORY: an allocation failure (named by stage natively: tests/bad_input, out_of_memory).
  const covered = new Set([...Object.keys(cases), 'IO_ERROR', 'INTERNAL', 'WASM_LOAD_FAILED', 'OUT_OF_MEMORY']);
  assert.deepEqual(documented.filter((c) => !covered.has(c)), []);
});

// A case object JSON cannot carry faithfully: NaN and Infinity (JSON.stringify writes null,
// and the core then reported a null), a cycle, a BigInt, nesting deeper than the stack: each
// is an INVALID_ARGUMENT naming where it is, never a RangeError or TypeError.
test('case objects that JSON cannot carry are INVALID_ARGUMENT errors naming the place', () => {
  const cyclic = planar({ outer: square });
  cyclic.self = cyclic;
  let deep = {};
  for (let i = 0; i < 5000; i++) deep = { a: deep };
  const bad = [
    [planar({ outer: square }, { controlSpace: { hmax: NaN } }), /case\.controlSpace\.hmax: expected a finite number, got NaN/],
    [planar({ outer: [line([Infinity, 0], [1, 0]), ...square.slice(1)] }), /case\.domain\.outer\[0\]\.p1\[0\]: expected a finite number/],
    [cyclic, /case\.self: the case refers to itself/],
    [planar({ outer: square }, { controlSpace: { hmax: 10n } }), /case\.controlSpace\.hmax: a BigInt/],
    [deep, /nested more than 256 levels/],
  ];
  for (const [c, message] of bad) {
    assert.throws(() => am.meshCase(c), (e) => e instanceof AnisomeshError && e.code === 'INVALID_ARGUMENT' && message.test(e.message));
  }
  assert.ok(am.meshCase(planar({ outer: square })).mesh.triangles.length > 0, 'the module keeps working');
});

test('an unknown meshCase or remesh option is an INVALID_ARGUMENT naming it (a typo is not ignored)', () => {
  assert.throws(() => am.meshCase(planar({ outer: square }), { frobnicate: true }),
    (e) => e instanceof AnisomeshError && e.code === 'INVALID_ARGUMENT' && /options\.frobnicate: unknown option/.test(e.message));
  assert.throws(() => am.meshCase(planar({ outer: square }), { onprogress: () => false }), /options\.onprogress/);
  const { mesh } = am.meshCase(planar({ outer: square }));
  assert.throws(() => am.remesh(mesh, null, { hsize: 0.05 }),
    (e) => e instanceof AnisomeshError && e.code === 'INVALID_ARGUMENT' && /options\.hsize: unknown option/.test(e.message));
});
