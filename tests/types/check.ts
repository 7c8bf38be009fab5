// Compiled with tsc --strict by tests/node/types.test.mjs, then run: the declared types must
// compile against real use, and every declared field of the reports must be what the
// functions return (same keys, same JS types), for planar, surface and remesh runs.
import { loadAnisomesh, AnisomeshError } from 'anisomesh';
import type { Case, PlanarCase, SurfaceCase, PlanarMeshStats, SurfaceMeshStats, MeshStats, AnisomeshErrorCode, MeshArrays } from 'anisomesh';
import { readFileSync } from 'node:fs';

type Kind = 'number' | 'boolean' | 'object' | 'string';
// Exhaustive key lists: a key missing here or not declared in the type is a compile error.
const planarKeys = {
  vertices: 'number', triangles: 'number', quads: 'number', edges: 'number', inverted: 'number', degenerate: 'number',
  boundaryLoops: 'number', boundaryPoints: 'number', controlNodes: 'number', controlElements: 'number',
  largestNeighbourSizeRatio: 'number', edgeLength: 'object', quality: 'object', boundaryUpdates: 'object',
  pipelineSeconds: 'object', timings: 'object', notes: 'object',
} as const satisfies Record<keyof PlanarMeshStats, Kind>;
const surfaceKeys = {
  vertices: 'number', triangles: 'number', quads: 'number', inverted: 'number', patches: 'number', patchTriangles: 'object',
  rounds: 'number', sharedEdges: 'number', invalidations: 'number', boundaryUpdates: 'object', crossSharedSizeRatioMax: 'number', edgeLength: 'object',
  quality: 'object', quality3d: 'object', controlSpaceQueries: 'number', controlSpaceSeconds: 'number',
  curvatureEvaluations: 'number', curvatureSeconds: 'number', secondsTotal: 'number',
} as const satisfies Record<keyof SurfaceMeshStats, Kind>;
const quality3dKeys = {
  edges: 'number', inverted: 'number', qualityMin: 'number', qualityMean: 'number', edgeLengthMin: 'number',
  edgeLengthMax: 'number', edgeLengthMean: 'number', edgesWithinSqrt2: 'number', chordDeviationMax: 'number',
  chordDeviationMaxRelative: 'number', edgeChordDeviationMax: 'number', isoChordDeviationMax: 'number',
} as const satisfies Record<keyof SurfaceMeshStats['quality3d'], Kind>;
const boundaryUpdateKeys = {
  rounds: 'number', converged: 'boolean', invalidSegments: 'number', shortSegments: 'number', chordSources: 'number',
  proximitySources: 'number', refinedElements: 'number', maxChordDeviation: 'number', shortSegmentSources: 'number',
  rediscretizedContours: 'number',
} as const satisfies Record<keyof PlanarMeshStats['boundaryUpdates'], Kind>;

const problems: string[] = [];
function compare(what: string, value: object, keys: Record<string, Kind>): void {
  const actual = Object.keys(value).sort();
  const declared = Object.keys(keys).sort();
  for (const k of declared) if (!actual.includes(k)) problems.push(`${what}.${k}: declared, not returned`);
  for (const k of actual) if (!declared.includes(k)) problems.push(`${what}.${k}: returned, not declared`);
  for (const k of declared) {
    const v = (value as Record<string, unknown>)[k];
    if (v !== undefined && typeof v !== keys[k]) problems.push(`${what}.${k}: declared ${keys[k]}, is ${typeof v}`);
  }
}

const readCase = (path: string): Case => JSON.parse(readFileSync(new URL(`../../examples/${path}`, import.meta.url), 'utf8')) as Case;

// A case written inline: the union narrows on 'patches'.
const square: PlanarCase = {
  domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], ref: 1 }] },
  controlSpace: { hmax: 0.2, gradation: 2 },
  sources: [{ type: 'radial', center: [0.5, 0.5], metric: { h1: 0.02, h2: 0.1, alpha: 0.3 }, radius: 0.2 }],
};
const plane: SurfaceCase = {
  metric: { chordTolerance: 0.01, hmax: 0.3 },
  patches: [{ surface: { type: 'plane' }, sources: [{ type: 'radial', center: [0.5, 0.5], metric: { h1: 0.05 }, radius: 0.2 }] }],
};
function isSurface(c: Case): c is SurfaceCase {
  return 'patches' in c && c.patches !== undefined;
}

const am = await loadAnisomesh();
const planar = am.meshCase(square, { measures: true });
const planarStats: PlanarMeshStats | null = planar.stats;
if (!planarStats) throw new Error('no planar stats');
compare('planar', planarStats, planarKeys);
compare('planar.boundaryUpdates', planarStats.boundaryUpdates, boundaryUpdateKeys);
const edgesCount: number = planarStats.edges;
if (!(edgesCount > 0)) problems.push('planar.edges not positive');

// A deferred report: the result's report() gives the planar stats, once.
const quick = am.meshCase(square, { stats: false });
if (quick.stats !== null || !quick.report) throw new Error('stats: false gives no stats and a report()');
const later: PlanarMeshStats = quick.report();
compare('planar (deferred)', later, planarKeys);

const surface = am.meshCase(plane);
const surfaceStats: SurfaceMeshStats | null = surface.stats;
if (!surfaceStats) throw new Error('no surface stats');
compare('surface', surfaceStats, surfaceKeys);
compare('surface.quality3d', surfaceStats.quality3d, quality3dKeys);
// A surface run's deferred report: the same keys (its 3D measures made in report()).
const quickSurface = am.meshCase(plane, { stats: false, measures: true });
if (quickSurface.stats !== null || !quickSurface.report) throw new Error('surface stats: false gives no stats and a report()');
const laterSurface: SurfaceMeshStats = quickSurface.report();
compare('surface (deferred)', laterSurface, surfaceKeys);
compare('surface.quality3d (deferred)', laterSurface.quality3d, quality3dKeys);
const bareSurface = am.meshCase(plane, { stats: false, measures: true, elementMeasures: false });
const colours: { quality: Float32Array; edgeLength: Float32Array } = bareSurface.elementMeasures!();
if (!(colours.quality instanceof Float32Array) || !(colours.edgeLength instanceof Float32Array)) problems.push('elementMeasures() arrays');
bareSurface.dispose!();

// Examples read from disk, narrowed by the discriminant.
for (const file of ['point_source.json', 'surface/surface_sphere.json']) {
  const c = readCase(file);
  const r = am.meshCase(c);
  const s: MeshStats | null = r.stats;
  if (!s) throw new Error(`${file}: no stats`);
  if (isSurface(c) !== 'patches' in s) problems.push(`${file}: case kind and report kind disagree`);
  compare(file, s, isSurface(c) ? surfaceKeys : planarKeys);
}

const remeshed = am.remesh(planar.mesh, null, { hmax: 0.1, svg: true });
compare('remesh', remeshed.stats, planarKeys);
const svg: string | undefined = remeshed.svg;
if (!svg?.startsWith('<svg') && !svg?.startsWith('<?xml')) problems.push('remesh svg missing');
// stats: false: no report at once, the same fields from report().
const stages: string[] = [];
const deferred = am.remesh(planar.mesh, null, { hmax: 0.1, stats: false, onStage: (name: string) => { stages.push(name); } });
const none: null = deferred.stats;
if (none !== null) problems.push('remesh stats: false: stats not null');
compare('remesh report()', deferred.report(), planarKeys);
if (stages.join() !== 'boundary,control space,discretization,meshing,output') problems.push(`remesh onStage: ${stages.join()}`);

// Binary Medit: bytes out, bytes in, the same mesh; text formats stay strings.
const meshb: Uint8Array = am.writeMesh(planar.mesh, 'meshb');
if (!(meshb instanceof Uint8Array) || meshb[0] !== 1 || meshb[4] !== 2) problems.push('meshb: not a version 2 Uint8Array');
const fromMeshb = am.readMesh(meshb, 'meshb');
if (fromMeshb.triangles?.length !== planar.mesh.triangles?.length) problems.push('meshb: triangles differ');
const medit: string = am.writeMesh(planar.mesh, 'mesh');
if (typeof medit !== 'string') problems.push('mesh: not a string');
const fromBytes: MeshArrays = am.readMesh(new TextEncoder().encode(medit));
if (fromBytes.triangles?.length !== planar.mesh.triangles?.length) problems.push('mesh bytes: triangles differ');

let code: AnisomeshErrorCode | null = null;
try {
  am.metric({ h: -1 });
} catch (e) {
  if (e instanceof AnisomeshError) code = e.code;
}
if (code !== 'INVALID_METRIC') problems.push(`error code ${code}`);

console.log(JSON.stringify({ problems, planarEdges: planarStats.edges, surfaceTriangles: surfaceStats.triangles }));
