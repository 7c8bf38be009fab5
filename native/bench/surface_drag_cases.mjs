// The surface drag cases of issue #12 shared by the drag benches: "Surface p2 with holes"
// with a radial source moved along u (step k puts it at u = 0.1 k), as is and refined to
// about 50k triangles (chord tolerance 0.0025, hmax 0.3).
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { dragSource, refinedP2Metric } from '../../tests/browser/fixtures.mjs';

export function surfaceDragCases(root) {
  const p2 = JSON.parse(readFileSync(join(root, 'examples/surface/surface_p2_holes.json'), 'utf8'));
  const withSource = (c, x) => {
    const out = structuredClone(c);
    out.patches[0].sources = [dragSource(x)];
    return out;
  };
  const refined = structuredClone(p2);
  Object.assign(refined.metric, refinedP2Metric);
  return [
    ['p2 with holes + radial source', (k) => withSource(p2, 0.1 * k)],
    ['p2 refined + radial source', (k) => withSource(refined, 0.1 * k)],
  ];
}
