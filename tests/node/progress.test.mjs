// Cancellation through the npm package on hostile cases (issue #15): an always-false
// onProgress is called exactly once and the run then throws CANCELLED (no callback after
// the first false, no mesh); cancelling at the k-th callback gives exactly k callbacks.
// The order of events only; native/bench/progress_latency.mjs prints the times.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const bad = (name) => readFileSync(new URL(`../bad_input/${name}`, import.meta.url), 'utf8');
// [case, k]: k callbacks come before the run ends by itself (the sphere reaches
// ELEMENT_BUDGET_EXCEEDED, its patch's element estimate, after its first callback).
const cases = {
  maxlevel_20: [bad('maxlevel_20.json'), 3],
  oscillating_expression: [bad('oscillating_expression.json'), 3],
  sphere_chord_1e_12: [bad('sphere_chord_1e-12.json'), 1],
  square_hmax_0_005: [
    JSON.stringify({
      domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] },
      controlSpace: { hmax: 0.005 },
    }),
    3,
  ],
};

function cancelAt(text, k) {
  const events = [];
  try {
    am.meshCase(text, {
      maxElements: 5000000,
      onProgress: (fraction) => {
        events.push(typeof fraction === 'number' && fraction >= 0 && fraction <= 1 ? 'callback' : `bad fraction ${fraction}`);
        return events.length < k;
      },
    });
    events.push('returned');
  } catch (e) {
    events.push(e instanceof AnisomeshError ? e.code : `threw ${e}`);
  }
  return events;
}

for (const [name, [text, k]] of Object.entries(cases)) {
  test(`${name}: an always-false onProgress is called once, then CANCELLED`, () => {
    assert.deepEqual(cancelAt(text, 1), ['callback', 'CANCELLED']);
  });
  test(`${name}: cancelling at callback ${k} gives ${k} callbacks, then CANCELLED`, () => {
    assert.deepEqual(cancelAt(text, k), [...Array(k).fill('callback'), 'CANCELLED']);
  });
}
