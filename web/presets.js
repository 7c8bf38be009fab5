// Presets: named cases the app can start from.
//
// A preset is { id, label, group, surface, load() -> case object }.
//   surface: false -> the case is meshed with meshCase (planar, mesh.dimension 2)
//   surface: true  -> a surface case (examples/SURFACE_FORMAT.md), also meshed with
//                     meshCase; the mesh has dimension 3 and is shown in the 3D view and
//                     in the parameter (u, v) plane of the 2D view.

import { newSurfaceCase } from './surface_editor.js';

const example = (file) => async () => {
  const r = await fetch(new URL(`../examples/${file}`, import.meta.url));
  if (!r.ok) throw new Error(`cannot load examples/${file}: HTTP ${r.status}`);
  const c = await r.json();
  return c;
};

// Derived preset: a copy of an example with some fields changed.
const derived = (file, edit) => async () => {
  const c = await example(file)();
  edit(c);
  return c;
};

export const presets = [
  { id: 'holes-off', label: 'Rectangle with holes, dr off (fig. 6)', group: 'planar', surface: false, load: example('fig6_rect_holes_nosmooth.json') },
  { id: 'holes-dr8', label: 'Rectangle with holes, dr = 8 (fig. 7)', group: 'planar', surface: false, load: example('fig7_rect_holes_dr8.json') },
  { id: 'holes-dr2', label: 'Rectangle with holes, dr = 2 (fig. 7)', group: 'planar', surface: false, load: example('fig7_rect_holes_dr2.json') },
  { id: 'boundary-layer', label: 'Boundary-layer channel', group: 'planar', surface: false, load: example('boundary_layer.json') },
  { id: 'shear-layer', label: 'Circular shear layer', group: 'planar', surface: false, load: example('shear_layer.json') },
  { id: 'point-source', label: 'Point source', group: 'planar', surface: false, load: example('point_source.json') },
  {
    id: 'point-source-fine',
    label: 'Point source, fine (~40k triangles)',
    group: 'planar',
    surface: false,
    load: derived('point_source.json', (c) => {
      c.name = 'point_source_fine';
      c.sources[0].h0 = 0.0007;
      c.controlSpace.hmin = 0.0007;
      c.controlSpace.hmax = 0.012;
    }),
  },
  { id: 'p2-holes', label: 'Surface p2 with holes (fig. 10)', group: 'surface', surface: true, load: example('surface/surface_p2_holes.json') },
  { id: 'two-patch-c', label: 'Two patches, C contour, adapted (figs. 11-13)', group: 'surface', surface: true, load: example('surface/surface_two_patch_c.json') },
  { id: 'two-patch-c-noadapt', label: 'Two patches, C contour, not adapted', group: 'surface', surface: true, load: example('surface/surface_two_patch_c_noadapt.json') },
  { id: 'sphere', label: 'Sphere band', group: 'surface', surface: true, load: example('surface/surface_sphere.json') },
  { id: 'torus', label: 'Torus', group: 'surface', surface: true, load: example('surface/surface_torus.json') },
];

// New surfaces to edit in the panel's "Surface" folder.
presets.push(
  { id: 'new-heightfield', label: 'New surface: height field z = f(u, v)', group: 'surface', surface: true, load: async () => newSurfaceCase('heightfield') },
  { id: 'new-expression', label: 'New surface: x, y, z (u, v) expressions', group: 'surface', surface: true, load: async () => newSurfaceCase('expression') },
  { id: 'new-bezier', label: 'New surface: bicubic Bezier patch', group: 'surface', surface: true, load: async () => newSurfaceCase('bezier') },
);

export const defaultPresetId = 'holes-dr2';

export function presetById(id) {
  return presets.find((p) => p.id === id) ?? null;
}
