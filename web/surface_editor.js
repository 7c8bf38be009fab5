// The surface of a patch edited in the panel: its kind (plane, height field z = f(u, v),
// expression surface x, y, z (u, v), cylinder, sphere, torus, bicubic Bezier, the paper's
// p2), its parameters and its parameter range. The core checks everything (an expression
// is parsed there, and a parse error names the field and the column); the page only
// writes the case's JSON (examples/SURFACE_FORMAT.md).

const TAU = 2 * Math.PI;

// A 4 x 4 Bezier control net over [0, 2]^2 with a bump in the middle.
function bezierNet() {
  const rows = [];
  for (let i = 0; i < 4; i++) {
    const row = [];
    for (let j = 0; j < 4; j++) row.push([(2 * j) / 3, (2 * i) / 3, (i === 1 || i === 2) && (j === 1 || j === 2) ? 0.6 : 0]);
    rows.push(row);
  }
  return rows;
}

/** Defaults of each kind (a surface object of the case format). */
export const surfaceKinds = {
  heightfield: () => ({ type: 'heightfield', z: '0.3*sin(3*u)*cos(2*v)', domain: [[0, 0], [2, 2]] }),
  expression: () => ({ type: 'expression', x: '(1+0.3*v)*cos(u)', y: '(1+0.3*v)*sin(u)', z: 'v', domain: [[0, 0], [3, 1]] }),
  plane: () => ({ type: 'plane', origin: [0, 0, 0], a1: [1, 0, 0], a2: [0, 1, 0], domain: [[0, 0], [1, 1]] }),
  cylinder: () => ({ type: 'cylinder', radius: 1, center: [0, 0, 0], domain: [[0, 0], [3, 1.5]] }),
  sphere: () => ({ type: 'sphere', radius: 1, center: [0, 0, 0], domain: [[0, -1.2], [3, 1.2]] }),
  torus: () => ({ type: 'torus', majorRadius: 1, minorRadius: 0.35, center: [0, 0, 0], domain: [[0, 0], [3, TAU]] }),
  bezier: () => ({ type: 'bezier', points: bezierNet() }),
  p2: () => ({ type: 'p2', domain: [[-10, -10], [10, 10]] }),
};

// Fields of each kind shown in the panel: [key, label, kind ('text' | 'number'), slider range].
// The parameter range the core gives a surface whose case has no "domain" (kinds that
// require one are not listed): native/src/io/surface_case_json.cpp.
const caseDefaultDomain = {
  plane: () => [[0, 0], [1, 1]],
  sphere: () => [[0, -1.4], [TAU, 1.4]],
  cylinder: () => [[0, 0], [TAU, 1]],
  torus: () => [[0, 0], [TAU, TAU]],
};

const fields = {
  heightfield: [['z', 'z(u, v)', 'text']],
  expression: [['x', 'x(u, v)', 'text'], ['y', 'y(u, v)', 'text'], ['z', 'z(u, v)', 'text']],
  plane: [],
  cylinder: [['radius', 'radius', 'number', [0.05, 5]]],
  sphere: [['radius', 'radius', 'number', [0.05, 5]]],
  torus: [['majorRadius', 'major radius', 'number', [0.1, 5]], ['minorRadius', 'minor radius', 'number', [0.02, 2]]],
  bezier: [],
  p2: [],
};

/**
 * The "Surface" folder of the panel. ctx: { gui, controllers (target -> controller, for
 * inline errors), getCase(), edited(delay), onReplace() (the patch's contour was reset) }.
 */
export function createSurfaceEditor(ctx) {
  const folder = ctx.gui.addFolder('Surface');
  let inner = null;
  const pick = { patch: 0 };
  let patchCtrl = null;

  // The surface object a patch uses (inline, or by name from the case's "surfaces").
  const surfaceOf = (c, p) => {
    const patch = c.patches[p];
    return typeof patch.surface === 'string' ? c.surfaces?.[patch.surface] : patch.surface;
  };

  function rebuild() {
    inner?.destroy();
    patchCtrl?.destroy();
    for (const k of [...ctx.controllers.keys()]) if (k.startsWith('surface.')) ctx.controllers.delete(k);
    const c = ctx.getCase();
    if (!c || !Array.isArray(c.patches) || !c.patches.length) return;
    pick.patch = Math.min(pick.patch, c.patches.length - 1);
    const labels = {};
    c.patches.forEach((p, i) => { labels[`${i + 1}: ${p.name ?? 'patch'}`] = i; });
    patchCtrl = folder.add(pick, 'patch', labels).name('patch').onChange(() => { rebuild(); ctx.onPatch?.(); });
    inner = folder.addFolder(`Patch ${pick.patch + 1}`);
    const s = surfaceOf(c, pick.patch);
    if (!s) return;
    const kind = { type: s.type };
    ctx.controllers.set('surface.type', inner.add(kind, 'type', Object.keys(surfaceKinds)).name('kind').onChange((t) => {
      replaceSurface(c, pick.patch, surfaceKinds[t]());
      rebuild();
      ctx.onReplace();
      ctx.edited(0);
    }));
    for (const [key, label, type, range] of fields[s.type] ?? []) {
      const ctrl = type === 'number' ? inner.add(s, key, range[0], range[1]) : inner.add(s, key);
      ctrl.name(label).onFinishChange(() => ctx.edited(0));
      ctx.controllers.set(`surface.${key}`, ctrl);
    }
    if (s.type !== 'bezier') {
      // The parameter range [u0, u1] x [v0, v1]; the default outer contour follows it.
      // A case without a domain means the core's default range (io/surface_case_json.cpp), not
      // the open range a new surface of this kind starts with.
      s.domain ??= caseDefaultDomain[s.type]?.() ?? surfaceKinds[s.type]().domain;
      const d = {};
      const def = (name, i, j) => Object.defineProperty(d, name, {
        get: () => s.domain[i][j], set: (x) => { s.domain[i][j] = x; }, enumerable: true,
      });
      def('u0', 0, 0); def('u1', 1, 0); def('v0', 0, 1); def('v1', 1, 1);
      for (const k of ['u0', 'u1', 'v0', 'v1']) {
        const ctrl = inner.add(d, k).name(`${k[0]} ${k[1] === '0' ? 'min' : 'max'}`).onFinishChange(() => ctx.edited(0));
        ctx.controllers.set(`surface.domain.${k}`, ctrl);
      }
      ctx.controllers.set('surface.domain', ctx.controllers.get('surface.domain.u0'));
    }
  }

  // A new surface for patch p: its trimming goes back to the default (the parameter
  // rectangle) since the old contour and holes need not lie in the new range.
  function replaceSurface(c, p, surface) {
    const patch = c.patches[p];
    if (typeof patch.surface === 'string') c.surfaces[patch.surface] = surface;
    else patch.surface = surface;
    delete patch.outer;
    delete patch.holes;
    delete patch.sources;
    // Shared curves of this patch no longer match anything.
    if (c.shared) c.shared = c.shared.filter((sh) => ![sh.a?.patch, sh.b?.patch].some((q) => q === p || q === patch.name));
    if (!c.shared?.length) delete c.shared;
  }

  return {
    folder,
    rebuild,
    get patch() { return pick.patch; },
    /** Shows patch p (e.g. where a source was placed). */
    select(p) { pick.patch = p; rebuild(); ctx.onPatch?.(); },
    /** A new case: its first patch. */
    reset(p = 0) { pick.patch = p; },
    /** The control for a core error on patches[p].surface.<field> of the shown patch, else null. */
    targetOf(message) {
      const c = ctx.getCase();
      const m = /patches\[(\d+)\]\.surface\.(\w+)/.exec(message);
      if (m && Number(m[1]) === pick.patch) return `surface.${m[2]}`;
      const named = /surfaces\.(\w+)\.(\w+)/.exec(message);  // a surface given by name
      if (named && c?.patches?.[pick.patch]?.surface === named[1]) return `surface.${named[2]}`;
      return null;
    },
  };
}

/** A new one-patch surface case of the given kind (the page's "new surface"). */
export function newSurfaceCase(kind = 'heightfield') {
  return {
    name: `${kind} patch`,
    metric: { chordTolerance: 0.01, hmin: 0.005, hmax: 0.3, maxAspectRatio: 6, gradation: 2 },
    patches: [{ name: 'S', surface: surfaceKinds[kind]() }],
  };
}
