// The two views sharing one WebGL canvas:
//   2D: the parameter plane (u, v) with an orthographic camera (pan: drag, zoom: wheel),
//       the mesh, the control-space overlay and the metric sources with draggable handles;
//   3D: the mesh positions (surfaces, or a planar mesh optionally lifted by its size field)
//       with a perspective camera and OrbitControls.
// Mode '2d', '3d' or 'split' (side by side, scissored viewports of the same canvas).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { qualityColor, lengthColor, sizeColor, fieldColor } from './colors.js';
import { sourceOverlay } from './overlays.js';
import { drawEdgesInFaces, edgeColorTable, fillEdgeCodes } from './wireframe.js';

const BG = 0xf7f7f5;
const SVG_NS = 'http://www.w3.org/2000/svg';
const GUIDE_DASH = [6, 4];  // dash and gap of a source's guide lines, CSS pixels (WebGL and the drag overlay)
const FACE_PLAIN = [0.80, 0.85, 0.92];
const HANDLE_PICK_PX = 12;

export class Views {
  /**
   * container: element the canvas fills.
   * hooks: { onSelect(sourceIndex), onDrag(sourceIndex, key, [x, y], phase: 'start'|'move'|'end') }
   */
  constructor(container, hooks = {}, { antialias = true, preserveDrawingBuffer = true } = {}) {
    this.container = container;
    this.hooks = hooks;
    this.mode = 'split';
    // preserveDrawingBuffer: the canvas can be read back (tests, screenshots) at any time.
    this.renderer = new THREE.WebGLRenderer({ antialias, preserveDrawingBuffer });
    this.preserveDrawingBuffer = preserveDrawingBuffer;
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(BG);
    this.renderer.setScissorTest(true);
    this.canvas = this.renderer.domElement;
    this.canvas.tabIndex = 0;
    container.appendChild(this.canvas);
    this.framesRendered = 0;
    // While a handle is dragged the view it is dragged in shows the sources here, drawn by
    // the page's compositor, instead of in WebGL: a move then costs no WebGL frame (on a
    // software rasterizer a WebGL frame costs the GPU process 15-26 ms of CPU, a compositor
    // frame 13 ms, taken from the mesher: native/bench/webgl_frame_cost.mjs). The first
    // WebGL frame after the release draws them in WebGL again (see render()).
    this.dragOverlay = document.createElementNS(SVG_NS, 'svg');
    Object.assign(this.dragOverlay.style, { position: 'absolute', left: '0', top: '0', pointerEvents: 'none', display: 'none' });
    container.appendChild(this.dragOverlay);
    this.sourcesInOverlay = null;  // the view ('2d' | '3d') whose sources the overlay shows

    // --- 2D scene ---
    this.scene2 = new THREE.Scene();
    this.cam2 = new THREE.OrthographicCamera(-1, 1, 1, -1, -100, 100);
    this.cam2.position.set(0, 0, 10);
    this.view2 = { cx: 0, cy: 0, halfH: 1 };  // centre and half height in world units
    this.layers2 = {
      faces: new THREE.Group(), boundary: new THREE.Group(),
      control: new THREE.Group(), sources: new THREE.Group(),
    };
    Object.values(this.layers2).forEach((g, i) => { g.renderOrder = i; this.scene2.add(g); });
    // The cached image of the 2D mesh layers, drawn as one quad (see #render2D).
    this.antialias = antialias;
    this.blitScene = new THREE.Scene();
    this.blitCam = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.blit = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.MeshBasicMaterial({ depthTest: false, depthWrite: false }));
    this.blit.frustumCulled = false;
    this.blitScene.add(this.blit);

    // --- 3D scene ---
    this.scene3 = new THREE.Scene();
    this.cam3 = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.cam3.up.set(0, 0, 1);
    this.scene3.add(new THREE.HemisphereLight(0xffffff, 0x8890a0, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(1, -2, 3);
    this.cam3.add(sun);  // light follows the camera so every side reads
    this.scene3.add(this.cam3);
    this.group3 = new THREE.Group();
    this.scene3.add(this.group3);
    this.control3 = new THREE.Group();  // control-space ellipses drawn on a surface
    this.scene3.add(this.control3);
    this.sources3 = new THREE.Group();  // source handles on a surface
    this.scene3.add(this.sources3);
    // Surface sources live in one patch's (u, v): sourcePatch, drawn shifted as the patch
    // is in the 2D layout. placing: 'radial' | 'segment' while a click is to place a source.
    this.sourcePatch = 0;
    this.placing = null;
    this.handles3 = [];  // { source, key, xyz }

    // Materials are created once and shared: disposing the last user of a shader program
    // makes three.js delete it, and recompiling costs ~100 ms per program on software WebGL.
    const line = (o) => new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true, ...o });
    this.mats = {
      // The 2D line materials are 'transparent' so that three.js draws them in one list ordered
      // by the layers' renderOrder, after the (opaque) faces.
      // The faces are the bottom layer, so they may be opaque (drawn first anyway): no
      // blending, ~15 % less time per 2D frame on a software rasterizer. They turn
      // transparent when dimmed under the control-space overlay.
      face2: new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide, depthTest: false, transparent: false }),
      face3: new THREE.MeshLambertMaterial({
        vertexColors: true, side: THREE.DoubleSide, flatShading: true, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
      }),
      boundary2: line({}),
      boundary3: new THREE.LineBasicMaterial({ vertexColors: true }),
      csLines: new THREE.LineBasicMaterial({ color: 0x6a5acd, transparent: true, opacity: 0.35, depthTest: false }),
      csEllipses: line({}),
      srcShape: new THREE.LineBasicMaterial({ color: 0x2c3e50, depthTest: false, transparent: true, opacity: 0.85 }),
      srcShapeSel: new THREE.LineBasicMaterial({ color: 0xd35400, depthTest: false }),
      srcEllipse: new THREE.LineBasicMaterial({ color: 0xc0392b, depthTest: false, transparent: true, opacity: 0.85 }),
      srcEllipseSel: new THREE.LineBasicMaterial({ color: 0xd35400, depthTest: false }),
      srcGuide: new THREE.LineDashedMaterial({ color: 0x2c3e50, depthTest: false, transparent: true, opacity: 0.8 }),
      srcGuideSel: new THREE.LineDashedMaterial({ color: 0xd35400, depthTest: false, transparent: true, opacity: 0.8 }),
      handles: new THREE.PointsMaterial({ size: 11, sizeAttenuation: false, vertexColors: true, depthTest: false }),
    };
    // The element edges are drawn by the face materials (web/wireframe.js): one pass, no lines.
    const table = edgeColorTable(edgeTable);
    this.edgeUniforms = { 2: drawEdgesInFaces(this.mats.face2, table, 0), 3: drawEdgesInFaces(this.mats.face3, table, 0) };
    this.edgeLook = { by: 'off', dim: false, moving: false };

    this.#installPointer();
    // OrbitControls after our own listeners: ours run first and enable it only over the 3D viewport.
    this.controls = new OrbitControls(this.cam3, this.canvas);
    this.controls.enableDamping = false;
    this.controls.addEventListener('change', () => this.requestRender('3d'));
    // Large meshes: the edges are hidden while the camera moves and come back when it
    // stops (since they are drawn in the faces' pass this saves little: see web/README.md).
    this.hideEdgesAbove = 60000;  // edge count
    this.controls.addEventListener('start', () => this.#interacting(true));
    this.controls.addEventListener('end', () => this.#interacting(false));

    this.sources = [];
    this.selected = -1;
    this.handles = [];  // { source, key, x, y }
    this.showSources = true;
    this.mesh = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  // --- layout ---------------------------------------------------------------------------

  setMode(mode) {
    this.mode = mode;
    this.resize();
  }

  /** Viewport rectangles in CSS pixels relative to the canvas: { '2d'?: rect, '3d'?: rect }. */
  viewports() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (this.mode === '2d') return { '2d': { x: 0, y: 0, w, h } };
    if (this.mode === '3d') return { '3d': { x: 0, y: 0, w, h } };
    const half = Math.floor(w / 2);
    return { '2d': { x: 0, y: 0, w: half, h }, '3d': { x: half + 1, y: 0, w: w - half - 1, h } };
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.#updateCam2();
    const v3 = this.viewports()['3d'];
    if (v3) {
      this.cam3.aspect = v3.w / Math.max(v3.h, 1);
      this.cam3.updateProjectionMatrix();
    }
    this.requestRender();
  }

  #updateCam2() {
    this.cache2Valid = false;
    const v = this.viewports()['2d'];
    if (!v) return;
    const aspect = v.w / Math.max(v.h, 1);
    const { cx, cy, halfH } = this.view2;
    Object.assign(this.cam2, { left: cx - halfH * aspect, right: cx + halfH * aspect, top: cy + halfH, bottom: cy - halfH });
    this.cam2.updateProjectionMatrix();
  }

  /** World units per CSS pixel in the 2D view. */
  pixelSize2() {
    const v = this.viewports()['2d'];
    return v ? (2 * this.view2.halfH) / v.h : 1;
  }

  fit2D(bounds) {
    if (!bounds) return;
    const [x0, y0, x1, y1] = bounds;
    this.fitted2 = [...bounds];
    const v = this.viewports()['2d'] ?? { w: 1, h: 1 };
    const aspect = v.w / Math.max(v.h, 1);
    this.view2.cx = (x0 + x1) / 2;
    this.view2.cy = (y0 + y1) / 2;
    this.view2.halfH = 0.54 * Math.max(y1 - y0, (x1 - x0) / aspect, 1e-9);
    this.#updateCam2();
    this.#refreshSources();
    this.requestRender('2d');
  }

  fit3D() {
    const box = new THREE.Box3().setFromObject(this.group3);
    if (box.isEmpty()) return;
    const c = box.getCenter(new THREE.Vector3());
    const r = box.getSize(new THREE.Vector3()).length() / 2;
    this.fitted3 = { c: c.clone(), r };
    const dist = r / Math.sin((this.cam3.fov * Math.PI) / 360) * 1.2;
    this.controls.target.copy(c);
    const dir = this.mesh?.dimension === 3 ? new THREE.Vector3(1, -1.4, 0.9) : new THREE.Vector3(0.15, -1.1, 1.0);
    this.cam3.position.copy(c).addScaledVector(dir.normalize(), dist);
    this.cam3.near = dist / 100;
    this.cam3.far = dist * 100;
    this.cam3.updateProjectionMatrix();
    this.controls.update();
    this.requestRender('3d');
  }

  /**
   * Fits again a view whose last fit no longer frames the mesh: its size changed by more than
   * 1.5 times or it moved by more than a quarter of its size (a sphere's radius 1 -> 3, a new
   * parameter range). Small changes (a source dragged) keep the user's camera.
   */
  refitIfOutgrown() {
    const box = new THREE.Box3().setFromObject(this.group3);
    if (!box.isEmpty() && this.fitted3) {
      const c = box.getCenter(new THREE.Vector3()), r = box.getSize(new THREE.Vector3()).length() / 2;
      const f = this.fitted3;
      if (r > 1.5 * f.r || r < f.r / 1.5 || c.distanceTo(f.c) > 0.25 * f.r) this.fit3D();
    }
    const b = this.meshBounds2(), g = this.fitted2;
    if (b && g) {
      const size = (q) => Math.max(q[2] - q[0], q[3] - q[1]);
      const s = size(b), t = size(g);
      const moved = Math.hypot((b[0] + b[2] - g[0] - g[2]) / 2, (b[1] + b[3] - g[1] - g[3]) / 2);
      if (s > 1.5 * t || s < t / 1.5 || moved > 0.25 * t) this.fit2D(b);
    }
  }

  // --- rendering ------------------------------------------------------------------------

  /** Schedules a draw of one viewport ('2d', '3d') or of all (default) on the next frame. */
  requestRender(which = 'all') {
    // While a source handle is dragged only the 2D view is redrawn (see app.js draw()).
    if (this.dragging && which === 'all' && this.viewports()[this.dragView ?? '2d']) which = this.dragView ?? '2d';
    (this.dirty ??= new Set()).add(which);
    if (this.renderPending) return;
    this.renderPending = true;
    requestAnimationFrame(() => { this.renderPending = false; this.render(); });
  }

  /**
   * Draws the dirty viewports now (all when called directly). With preserveDrawingBuffer
   * the other viewport keeps its pixels, so dragging a source redraws only the 2D half:
   * with software WebGL the fill rate is what limits the frame rate.
   */
  render() {
    const dirty = this.dirty ?? new Set(['all']);
    this.dirty = new Set();
    if (this.sourcesInOverlay && !this.dragging) {  // the drag is over: the sources go back to WebGL
      dirty.add(this.sourcesInOverlay);
      this.sourcesInOverlay = null;
      this.layers2.sources.visible = true;
      this.sources3.visible = true;
      this.dragOverlay.style.display = 'none';
    }
    const all = dirty.has('all') || !this.preserveDrawingBuffer;
    // A frame already drawn by renderNow() leaves its animation frame with nothing to draw.
    if (!all && !Object.keys(this.viewports()).some((k) => dirty.has(k))) return;
    const W = this.container.clientWidth, H = this.container.clientHeight;
    if (all) {
      this.renderer.setScissor(0, 0, W, H);
      this.renderer.setViewport(0, 0, W, H);
      this.renderer.clear();
    }
    for (const [kind, v] of Object.entries(this.viewports())) {
      if (!all && !dirty.has(kind)) continue;
      // WebGL's y axis points up; autoClear clears inside the scissor only.
      this.renderer.setViewport(v.x, H - v.y - v.h, v.w, v.h);
      this.renderer.setScissor(v.x, H - v.y - v.h, v.w, v.h);
      if (kind === '2d') this.#render2D(v);
      else this.renderer.render(this.scene3, this.cam3);
    }
    this.framesRendered++;
  }

  /**
   * Draws the first of `order` ('2d', '3d') shown now and the others on the next frame.
   * sync: wait until the GPU has finished the drawing (a 1-pixel read back; measurements only).
   */
  renderNow(order, { sync = false } = {}) {
    const shown = order.filter((k) => this.viewports()[k]);
    if (!this.preserveDrawingBuffer || !shown.length) {
      this.dirty = new Set(['all']);
      this.render();
    } else {
      this.dirty = new Set([shown[0]]);
      this.render();
      for (const k of shown.slice(1)) this.requestRender(k);
    }
    if (sync) {
      const gl = this.renderer.getContext();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    }
  }

  /**
   * The 2D view: the mesh layers (faces, edges, boundary, control-space overlay) are drawn
   * into an offscreen image that is kept until they or the camera change; a frame is that
   * image plus the sources on top. Moving a source handle then costs a textured quad and
   * a few lines instead of the whole mesh, which on a software rasterizer keeps its
   * frames from queueing up in front of the next mesh.
   */
  #render2D(v) {
    const r = this.renderer;
    const ratio = r.getPixelRatio();
    const w = Math.max(1, Math.round(v.w * ratio)), h = Math.max(1, Math.round(v.h * ratio));
    let rt = this.cache2;
    if (!rt || rt.width !== w || rt.height !== h) {
      rt?.dispose();
      rt = this.cache2 = new THREE.WebGLRenderTarget(w, h, {
        depthBuffer: false, samples: this.antialias ? 4 : 0, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
      });
      rt.texture.colorSpace = THREE.SRGBColorSpace;  // 8-bit sRGB storage, decoded when drawn: no banding
      this.blit.material.map = rt.texture;
      this.blit.material.needsUpdate = true;
      this.cache2Valid = false;
    }
    const layers = this.layers2;
    if (!this.cache2Valid) {
      const sourcesShown = layers.sources.visible;
      layers.sources.visible = false;
      r.setRenderTarget(rt);
      r.clear();
      r.render(this.scene2, this.cam2);
      r.setRenderTarget(null);
      layers.sources.visible = sourcesShown;
      this.cache2Valid = true;
      this.cache2Draws = (this.cache2Draws ?? 0) + 1;
    }
    r.render(this.blitScene, this.blitCam);  // clears the viewport (autoClear) and copies the image
    const others = [layers.faces, layers.boundary, layers.control];
    const shown = others.map((g) => g.visible);
    others.forEach((g) => { g.visible = false; });
    const autoClear = r.autoClear;
    r.autoClear = false;
    r.render(this.scene2, this.cam2);
    r.autoClear = autoClear;
    others.forEach((g, i) => { g.visible = shown[i]; });
  }

  /** The 2D mesh layers or the 2D camera changed: redraw them (not just the sources). */
  invalidate2D() {
    this.cache2Valid = false;
  }

  #interacting(on) {
    this.edgeLook.moving = on && (this.edgeCount ?? 0) > this.hideEdgesAbove;
    this.#edgeOpacity();
    if (!on) this.requestRender('3d');
  }

  // The edges' opacity in each view: by colouring ('length', 'plain', 'off'), faded under
  // the control-space overlay (2D), hidden while the camera moves (3D, large meshes).
  #edgeOpacity() {
    const { by, dim, moving } = this.edgeLook;
    const length = by === 'length';
    this.edgeUniforms[2].edgeOpacity.value = by === 'off' ? 0 : dim ? (length ? 0.3 : 0.2) : (length ? 0.95 : 0.55);
    this.edgeUniforms[3].edgeOpacity.value = by === 'off' || moving ? 0 : length ? 0.9 : 0.45;
  }

  // --- mesh -----------------------------------------------------------------------------

  /**
   * Shows a mesh result from the worker: { mesh, measures: { edges, edgeLength, quality, vertexH } }.
   * style: { colorBy: 'quality'|'field'|'none', edges: 'length'|'plain'|'off', lift, hmax }
   */
  setMesh(result, style) {
    this.mesh = result.mesh;
    this.result = result;
    this.#buildMesh(style);
  }

  setStyle(style) {
    if (this.result) this.#buildMesh(style);
  }

  // Geometry is reused between meshes: the objects stay in the scenes and their typed
  // arrays are refilled in place (grown with some slack when a mesh is larger), so a
  // remesh while dragging uploads the used range with bufferSubData instead of
  // allocating new GPU buffers. A flat planar mesh shares one geometry between the 2D
  // and the 3D view (uploaded once); flat shading needs no normals.
  #buildMesh(style) {
    const { mesh, measures } = this.result;
    const nv = mesh.params.length / 2;
    const flat = mesh.dimension === 2 && !(style.lift > 0 && measures.vertexH);
    const uvPos = this.#scratch('uv', 3 * nv);
    for (let i = 0; i < nv; i++) { uvPos[3 * i] = mesh.params[2 * i]; uvPos[3 * i + 1] = mesh.params[2 * i + 1]; uvPos[3 * i + 2] = 0; }
    // Several surface patches: each drawn in its own (u, v) plane, side by side (see patchLayout).
    const layout = this.layout = patchLayout(mesh, this.result.patches);
    let pos3 = mesh.positions;
    if (mesh.dimension === 2 && !flat) {
      // Lift the plane by the log of the requested size: refinement shows as valleys/peaks.
      pos3 = this.#scratch('lift', 3 * nv);
      pos3.set(mesh.positions.subarray(0, 3 * nv));
      const hs = measures.vertexH;
      let hmin = Infinity, hmax = 0;
      for (let i = 0; i < hs.length; i++) { const h = hs[i]; if (h < hmin) hmin = h; if (h > hmax) hmax = h; }
      const span = Math.log(hmax / hmin) || 1;
      const size = this.#extent(uvPos, nv);
      for (let i = 0; i < nv; i++) pos3[3 * i + 2] = style.lift * 0.35 * size * (Math.log(hmax / hs[i]) / span);
    }
    const g = this.#meshObjects();
    const nt = mesh.triangles.length / 3, nq = mesh.quads.length / 4;
    const faceVerts = 3 * (nt + 2 * nq);
    const quality = style.colorBy === 'quality' ? measures.quality : null;
    const field = style.colorBy === 'field' ? measures.field : null;  // per vertex (adaptation mode)
    const faceCol = this.#attribute(g.faces2, 'color', faceVerts);
    fillFaceColors(faceCol.array, mesh, quality, field);
    if (layout) fillFacesLaidOut(this.#attribute(g.faces2, 'position', faceVerts).array, mesh, layout);
    else fillFaces(this.#attribute(g.faces2, 'position', faceVerts).array, mesh, uvPos);
    // The element edges, drawn by the faces (web/wireframe.js): each triangle's sides, in
    // each patch's own (u, v) in 2D (a shared curve once per patch). Lengths per edge are
    // not measured for laid-out surfaces: plain colours there.
    const edges = style.edges !== 'off' ? measures.edges : null;
    this.edgeCount = edges ? edges.length / 2 : 0;
    const lengths = style.edges === 'length' ? measures.edgeLength : null;
    const edgeCodes = this.#attribute(g.faces2, 'edgeCode', faceVerts).array;
    if (edges) {
      const codes = lengths && !layout ? this.#scratch('edgeRow', lengths.length) : null;
      if (codes) for (let e = 0; e < lengths.length; e++) codes[e] = lutIndex(0.5 + 0.5 * Math.log2(Math.max(lengths[e], 1e-6))) / 3;
      fillEdgeCodes(edgeCodes, mesh, edges, codes, PLAIN_EDGE_ROW);
    }
    this.edgeLook.by = !edges ? 'off' : lengths ? 'length' : 'plain';
    this.#edgeOpacity();
    this.#share(g.faces3, g.faces2, flat, faceVerts);
    if (!flat) fillFaces(this.#attribute(g.faces3, 'position', faceVerts).array, mesh, pos3);

    const bVerts = mesh.edges?.length ?? 0;
    const b2Verts = layout ? layout.boundary.length : bVerts;
    this.#attribute(g.boundary2, 'color', Math.max(bVerts, b2Verts)).array.fill(0.1, 0, 3 * Math.max(bVerts, b2Verts));
    if (layout) fillSegments(this.#attribute(g.boundary2, 'position', b2Verts).array, layout.boundary, layout.uv);
    else fillSegments(this.#attribute(g.boundary2, 'position', bVerts).array, mesh.edges, uvPos);
    this.#share(g.boundary3, g.boundary2, flat, bVerts);
    if (!flat) fillSegments(this.#attribute(g.boundary3, 'position', bVerts).array, mesh.edges, pos3);

    this.cache2Valid = false;
    // Bounds of the used range (the arrays' slack holds stale values): fit3D reads them.
    const box = boundsOf(flat ? uvPos : pos3, nv);
    for (const geom of [g.faces2, g.faces3, g.boundary2, g.boundary3]) {
      if (layout && geom === g.boundary2) geom.setDrawRange(0, layout.boundary.length);
      geom.boundingBox = box.clone();
      geom.boundingSphere = box.getBoundingSphere(new THREE.Sphere());
    }
    this.requestRender();
  }

  /** The persistent objects drawing the mesh (created on first use). */
  #meshObjects() {
    if (this.meshObjects) return this.meshObjects;
    const g = {};
    for (const k of ['faces2', 'faces3', 'boundary2', 'boundary3']) g[k] = new THREE.BufferGeometry();
    const add = (group, obj) => { obj.frustumCulled = false; group.add(obj); return obj; };
    add(this.layers2.faces, new THREE.Mesh(g.faces2, this.mats.face2));
    g.mesh3 = add(this.group3, new THREE.Mesh(g.faces3, this.mats.face3));
    add(this.layers2.boundary, new THREE.LineSegments(g.boundary2, this.mats.boundary2));
    add(this.group3, new THREE.LineSegments(g.boundary3, this.mats.boundary3));
    this.meshObjects = g;
    return g;
  }

  /**
   * geom's attribute `name` (3 floats per vertex) holding at least `count` vertices: the
   * existing one when it is large enough (marked for upload of the used range), else a
   * new one with 25 % slack. Sets the draw range to count.
   */
  #attribute(geom, name, count) {
    let attr = geom.getAttribute(name);
    if (!attr || attr.array.length < 3 * count) {
      if (attr) {
        // Frees the GPU buffers of the smaller arrays. The 2D and 3D geometries share
        // attributes (colours, edge codes, flat positions): the other one is released too, or
        // its vertex array state keeps drawing the freed buffers (black or stale faces).
        geom.dispose();
        this.#partnerOf(geom)?.dispose();
      }
      attr = new THREE.BufferAttribute(new Float32Array(Math.ceil(3 * count * 1.25) + 3), 3);
      attr.setUsage(THREE.DynamicDrawUsage);
      geom.setAttribute(name, attr);
    } else {
      attr.clearUpdateRanges();
      attr.addUpdateRange(0, 3 * count);
      attr.needsUpdate = true;
    }
    geom.setDrawRange(0, count);
    return attr;
  }

  /** The geometry that shares attributes with geom (faces2 <-> faces3, boundary2 <-> boundary3). */
  #partnerOf(geom) {
    const g = this.meshObjects;
    if (!g) return null;
    return { [g.faces2.id]: g.faces3, [g.faces3.id]: g.faces2, [g.boundary2.id]: g.boundary3, [g.boundary3.id]: g.boundary2 }[geom.id] ?? null;
  }

  // The 3D geometry draws the 2D one's arrays (flat planar mesh: no upload of its own),
  // or its own positions; the colours (and the faces' edge codes) are always the 2D geometry's.
  #share(geom3, geom2, shared, count) {
    const pos2 = geom2.getAttribute('position'), col2 = geom2.getAttribute('color'), codes2 = geom2.getAttribute('edgeCode');
    if (codes2) geom3.setAttribute('edgeCode', codes2);
    if (shared) {
      if (geom3.getAttribute('position') && geom3.getAttribute('position') !== pos2) {
        geom3.dispose();  // its own positions' buffer; geom2 shares its other buffers (see #attribute)
        geom2.dispose();
      }
      geom3.setAttribute('position', pos2);
    } else if (geom3.getAttribute('position') === pos2) {
      geom3.deleteAttribute('position');
    }
    geom3.setAttribute('color', col2);
    geom3.setDrawRange(0, count);
  }

  /** A reusable Float32Array of at least n floats (its first n are what the caller fills). */
  #scratch(key, n) {
    (this.scratch ??= {});
    if (!this.scratch[key] || this.scratch[key].length < n) this.scratch[key] = new Float32Array(Math.ceil(n * 1.25));
    return this.scratch[key];
  }

  #extent(xyz, n = xyz.length / 3) {
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < 3 * n; i += 3) {
      x0 = Math.min(x0, xyz[i]); x1 = Math.max(x1, xyz[i]); y0 = Math.min(y0, xyz[i + 1]); y1 = Math.max(y1, xyz[i + 1]);
    }
    return Math.max(x1 - x0, y1 - y0);
  }

  /** Bounds [x0, y0, x1, y1] of the current mesh in the parameter plane. */
  meshBounds2() {
    if (!this.mesh) return null;
    if (this.layout) return this.layout.bounds;
    const p = this.mesh.params;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < p.length; i += 2) {
      x0 = Math.min(x0, p[i]); x1 = Math.max(x1, p[i]); y0 = Math.min(y0, p[i + 1]); y1 = Math.max(y1, p[i + 1]);
    }
    return [x0, y0, x1, y1];
  }

  // --- control-space overlay ------------------------------------------------------------

  /** overlay: { nodes: Float32Array (x, y, h1, h2, alpha), lines: Float32Array (x0, y0, x1, y1) } or null. */
  setControlSpace(overlay, visible) {
    this.cache2Valid = false;
    const g = this.layers2.control;
    for (const grp of [g, this.control3]) for (const o of [...grp.children]) { grp.remove(o); o.geometry.dispose(); }
    this.controlLegend = null;
    // Fade the mesh under the overlay so the ellipses read.
    const dim = Boolean(overlay && visible);
    const m = this.mats;
    m.face2.opacity = dim ? 0.35 : 1;
    if (m.face2.transparent !== dim) {
      m.face2.transparent = dim;
      m.face2.needsUpdate = true;
    }
    this.edgeLook.dim = dim;
    this.#edgeOpacity();
    if (!dim) { this.requestRender(); return; }
    if (overlay.glyphs) { this.#glyphOverlay(overlay.glyphs); return; }
    if (overlay.lines.length) {
      const n = overlay.lines.length / 2;
      const pos = new Float32Array(3 * n);
      for (let i = 0; i < n; i++) { pos[3 * i] = overlay.lines[2 * i]; pos[3 * i + 1] = overlay.lines[2 * i + 1]; }
      const geom = new THREE.BufferGeometry();
      geom.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      g.add(new THREE.LineSegments(geom, this.mats.csLines));
    }
    // Ellipses at nodes: the shape and orientation of each metric, scaled to the node
    // spacing so all are readable; the colour gives the size (log scale).
    const nodes = overlay.nodes, count = nodes.length / 5;
    if (count) {
      let hmin = Infinity, hmax = 0;
      for (let i = 0; i < count; i++) { hmin = Math.min(hmin, nodes[5 * i + 2]); hmax = Math.max(hmax, nodes[5 * i + 3]); }
      const b = overlay.bounds;
      const spacing = b ? Math.sqrt(((b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1])) / count) : 1;
      const seg = 20;
      const pos = new Float32Array(count * seg * 6), col = new Float32Array(count * seg * 6);
      const span = Math.log(hmax / hmin) || 1;
      for (let i = 0; i < count; i++) {
        const [x, y, h1, h2, a] = nodes.subarray(5 * i, 5 * i + 5);
        const s = (0.42 * spacing) / Math.max(h1, h2);
        const c = sizeColor(Math.log(h1 / hmin) / span);
        const ca = Math.cos(a), sa = Math.sin(a);
        for (let k = 0; k < seg; k++) {
          for (let e = 0; e < 2; e++) {
            const t = ((k + e) / seg) * 2 * Math.PI;
            const u = s * h1 * Math.cos(t), v = s * h2 * Math.sin(t);
            const o = 6 * (i * seg + k) + 3 * e;
            pos[o] = x + u * ca - v * sa; pos[o + 1] = y + u * sa + v * ca;
            col.set(c, o);
          }
        }
      }
      const geom = new THREE.BufferGeometry();
      geom.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      geom.setAttribute('color', new THREE.BufferAttribute(col, 3));
      g.add(new THREE.LineSegments(geom, this.mats.csEllipses));
      this.controlLegend = { hmin, hmax, count };
    }
    this.requestRender('2d');
  }

  // A surface's control spaces: the core's ellipses (half the requested sizes) in each
  // patch's (u, v), shifted as the patch is in the 2D view, and the same on the surface
  // in 3D; coloured by the ellipse's size in 3D (log scale).
  #glyphOverlay({ patch, offsets, uv, xyz }) {
    const count = patch.length;
    let nseg = 0;
    for (let i = 0; i < count; i++) nseg += offsets[i + 1] - offsets[i];
    const pos2 = new Float32Array(6 * nseg), pos3 = new Float32Array(6 * nseg), col = new Float32Array(6 * nseg);
    const sizes = new Float64Array(count);
    for (let i = 0; i < count; i++) {
      let r = 0;
      for (let k = offsets[i]; k < offsets[i + 1]; k++) {
        for (let j = k + 1; j < offsets[i + 1]; j++) {
          r = Math.max(r, Math.hypot(xyz[3 * k] - xyz[3 * j], xyz[3 * k + 1] - xyz[3 * j + 1], xyz[3 * k + 2] - xyz[3 * j + 2]));
        }
      }
      sizes[i] = r || 1e-12;
    }
    let hmin = Infinity, hmax = 0;
    for (const h of sizes) { hmin = Math.min(hmin, h); hmax = Math.max(hmax, h); }
    const span = Math.log(hmax / hmin) || 1;
    const shift = this.layout?.shift ?? null;
    let o = 0;
    for (let i = 0; i < count; i++) {
      const c = sizeColor(Math.log(sizes[i] / hmin) / span);
      const du = shift ? shift[patch[i]] ?? 0 : 0;
      const a = offsets[i], n = offsets[i + 1] - a;
      for (let k = 0; k < n; k++) {
        for (const j of [a + k, a + ((k + 1) % n)]) {
          pos2[o] = uv[2 * j] + du; pos2[o + 1] = uv[2 * j + 1]; pos2[o + 2] = 0;
          pos3[o] = xyz[3 * j]; pos3[o + 1] = xyz[3 * j + 1]; pos3[o + 2] = xyz[3 * j + 2];
          col.set(c, o);
          o += 3;
        }
      }
    }
    const add = (group, pos, mat) => {
      const geom = new THREE.BufferGeometry();
      geom.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      geom.setAttribute('color', new THREE.BufferAttribute(col, 3));
      const obj = new THREE.LineSegments(geom, mat);
      obj.frustumCulled = false;
      group.add(obj);
    };
    add(this.layers2.control, pos2, this.mats.csEllipses);
    add(this.control3, pos3, this.mats.csEllipses3 ??= new THREE.LineBasicMaterial({ vertexColors: true }));
    // 3D sizes of the ellipses (their longest diameter: the requested size along the larger axis).
    this.controlLegend = { hmin, hmax, count };
    this.requestRender();
  }

  // --- sources and handles --------------------------------------------------------------

  /** sources: the case's sources array (read only here); selected: index or -1. */
  setSources(sources, selected, visible = true) {
    this.sources = sources ?? [];
    this.selected = selected;
    this.showSources = visible;
    this.#refreshSources();
  }

  /** The u shift of the source patch in the 2D layout (0 without one). */
  sourceShift() {
    return this.layout?.shift[this.sourcePatch] ?? 0;
  }

  #refreshSources() {
    const g = this.layers2.sources;
    for (const grp of [g, this.sources3]) for (const o of [...grp.children]) { grp.remove(o); o.geometry.dispose(); }
    this.handles = [];
    this.handles3 = [];
    if (!this.showSources) { this.dragOverlay.innerHTML = ''; this.requestRender(); return; }
    const du = this.sourceShift();
    const px = this.pixelSize2();
    for (const m of [this.mats.srcGuide, this.mats.srcGuideSel]) { m.dashSize = GUIDE_DASH[0] * px; m.gapSize = GUIDE_DASH[1] * px; }
    const handlePos = [], handleCol = [];
    this.sources.forEach((s, i) => {
      const sel = i === this.selected;
      const { lines, handles } = sourceOverlay(s);
      for (const { points, kind } of lines) {
        const geom = new THREE.BufferGeometry();
        geom.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(points.flatMap(([x, y]) => [x + du, y, 0])), 3));
        const name = { ellipse: 'srcEllipse', guide: 'srcGuide', shape: 'srcShape' }[kind] + (sel ? 'Sel' : '');
        const mat = this.mats[name];
        const line = new THREE.Line(geom, mat);
        if (kind === 'guide') line.computeLineDistances();
        g.add(line);
      }
      for (const h of handles) {
        this.handles.push({ source: i, key: h.key, x: h.p[0] + du, y: h.p[1] });
        handlePos.push(h.p[0] + du, h.p[1], 0);
        handleCol.push(...(sel ? [0.83, 0.33, 0.0] : [0.17, 0.24, 0.31]));
      }
    });
    if (handlePos.length) {
      const geom = new THREE.BufferGeometry();
      geom.setAttribute('position', new THREE.Float32BufferAttribute(handlePos, 3));
      geom.setAttribute('color', new THREE.Float32BufferAttribute(handleCol, 3));
      g.add(new THREE.Points(geom, this.mats.handles));
    }
    // On a surface: the same handles at their points of the surface in the 3D view.
    if (this.mesh?.dimension === 3 && this.handles.length) {
      const pos = [], col = [];
      this.handles.forEach((h, k) => {
        const xyz = this.surfacePoint(this.sourcePatch, h.x - du, h.y);
        if (!xyz) return;
        this.handles3.push({ source: h.source, key: h.key, xyz });
        pos.push(...xyz);
        col.push(handleCol[3 * k], handleCol[3 * k + 1], handleCol[3 * k + 2]);
      });
      if (pos.length) {
        const geom = new THREE.BufferGeometry();
        geom.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
        geom.setAttribute('color', new THREE.Float32BufferAttribute(col, 3));
        const pts = new THREE.Points(geom, this.mats.handles);
        pts.renderOrder = 10;
        this.sources3.add(pts);
      }
    }
    const view = this.dragView ?? '2d';
    if (this.dragging && this.viewports()[view]) {
      // The first move draws one WebGL frame without the sources; later moves none.
      if (!this.sourcesInOverlay) {
        this.sourcesInOverlay = view;
        (view === '2d' ? g : this.sources3).visible = false;
        this.requestRender(view);
      }
      this.#drawSourcesOverlay();
      return;
    }
    this.requestRender(this.handles3.length ? 'all' : '2d');
  }

  /**
   * The sources of the view being dragged in, as #refreshSources puts them in WebGL (2D: the
   * layers2.sources lines and handles; 3D: the sources3 handles), drawn in the SVG overlay.
   */
  #drawSourcesOverlay() {
    const view = this.sourcesInOverlay;
    const v = this.viewports()[view];
    const svg = this.dragOverlay;
    Object.assign(svg.style, { left: `${v.x}px`, top: `${v.y}px`, width: `${v.w}px`, height: `${v.h}px`, display: '' });
    svg.setAttribute('viewBox', `0 0 ${v.w} ${v.h}`);
    // World -> viewport pixels through the view's camera (NDC: x right, y up).
    const cam = view === '2d' ? this.cam2 : this.cam3;
    const ndc = new THREE.Vector3();
    const px = (x, y, z = 0) => {
      ndc.set(x, y, z).project(cam);
      return [(ndc.x + 1) * 0.5 * v.w, (1 - ndc.y) * 0.5 * v.h, ndc.z];
    };
    const css = (m) => `#${m.color.getHexString()}`;
    const parts = [];
    for (const o of (view === '2d' ? this.layers2.sources : this.sources3).children) {
      const pos = o.geometry.getAttribute('position');
      if (o.isPoints) {
        const col = o.geometry.getAttribute('color');
        const size = this.mats.handles.size;
        for (let i = 0; i < pos.count; i++) {
          const [cx, cy, z] = px(pos.getX(i), pos.getY(i), pos.getZ(i));
          if (!(Math.abs(z) <= 1)) continue;  // behind the camera or clipped
          const rgb = [col.getX(i), col.getY(i), col.getZ(i)].map((c) => Math.round(255 * c)).join(',');
          parts.push(`<rect x="${(cx - size / 2).toFixed(1)}" y="${(cy - size / 2).toFixed(1)}" width="${size}" height="${size}" fill="rgb(${rgb})"/>`);
        }
        continue;
      }
      const pts = [];
      for (let i = 0; i < pos.count; i++) pts.push(px(pos.getX(i), pos.getY(i)).slice(0, 2).map((c) => c.toFixed(1)).join(','));
      const m = o.material;
      const dash = m.isLineDashedMaterial ? ` stroke-dasharray="${GUIDE_DASH.join(' ')}"` : '';
      parts.push(`<polyline points="${pts.join(' ')}" fill="none" stroke="${css(m)}" stroke-opacity="${m.transparent ? m.opacity : 1}" stroke-width="1"${dash}/>`);
    }
    svg.innerHTML = parts.join('');
  }

  // (u, v) of each corner of element e of a surface mesh, and its vertex ids.
  #corners(e) {
    const m = this.mesh, nt = m.triangles.length / 3, c = this.result.patches?.corners;
    const ids = e < nt ? [m.triangles[3 * e], m.triangles[3 * e + 1], m.triangles[3 * e + 2]]
      : [0, 1, 2, 3].map((k) => m.quads[4 * (e - nt) + k]);
    const base = e < nt ? 3 * e : 3 * nt + 4 * (e - nt);
    const uv = ids.map((v, k) => (c ? [c[2 * (base + k)], c[2 * (base + k) + 1]] : [m.params[2 * v], m.params[2 * v + 1]]));
    return { ids, uv };
  }

  /** The 3D point of a surface mesh at (u, v) of a patch (linear in its element), or null outside the mesh. */
  surfacePoint(patch, u, v) {
    const m = this.mesh;
    if (!m || m.dimension !== 3) return null;
    const elem = this.result.patches?.element, pos = m.positions;
    const ne = m.triangles.length / 3 + m.quads.length / 4;
    for (let e = 0; e < ne; e++) {
      if (elem && elem[e] !== patch) continue;
      const { ids, uv } = this.#corners(e);
      for (const tri of ids.length === 3 ? [[0, 1, 2]] : [[0, 1, 2], [0, 2, 3]]) {
        const [a, b, c] = tri.map((k) => uv[k]);
        const det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if (!det) continue;
        const l1 = ((u - a[0]) * (c[1] - a[1]) - (v - a[1]) * (c[0] - a[0])) / det;
        const l2 = ((b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0])) / det;
        const l0 = 1 - l1 - l2;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        const w = [l0, l1, l2];
        return [0, 1, 2].map((k) => tri.reduce((sum, t, j) => sum + w[j] * pos[3 * ids[t] + k], 0));
      }
    }
    return null;
  }

  /**
   * The point of the surface mesh under a client position in the 3D view: { patch, uv, xyz,
   * element }, with (u, v) interpolated in the element's own patch; null when it misses.
   */
  pick3D(clientX, clientY) {
    const v = this.viewports()['3d'];
    if (!v || !this.meshObjects || this.mesh?.dimension !== 3) return null;
    const r = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - r.left - v.x) / v.w) * 2 - 1, -((clientY - r.top - v.y) / v.h) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.cam3);
    const hit = ray.intersectObject(this.meshObjects.mesh3, false)[0];
    if (!hit) return null;
    const nt = this.mesh.triangles.length / 3, f = hit.faceIndex;
    const e = f < nt ? f : nt + Math.floor((f - nt) / 2);
    const tri = f < nt ? [0, 1, 2] : (f - nt) % 2 === 0 ? [0, 1, 2] : [0, 2, 3];
    const { ids, uv } = this.#corners(e);
    const P = (k) => new THREE.Vector3(...this.mesh.positions.subarray(3 * ids[k], 3 * ids[k] + 3));
    const w = new THREE.Triangle(P(tri[0]), P(tri[1]), P(tri[2])).getBarycoord(hit.point, new THREE.Vector3());
    const bary = [w.x, w.y, w.z];
    const at = (j) => tri.reduce((sum, t, i) => sum + bary[i] * uv[t][j], 0);
    return { patch: this.result.patches?.element[e] ?? 0, uv: [at(0), at(1)], xyz: hit.point.toArray(), element: e };
  }

  /** The patch whose strip of the 2D layout holds x (the source patch without a layout). */
  patchAt2(x) {
    const L = this.layout;
    if (!L) return this.sourcePatch;
    for (let p = 0; p < L.ranges.length; p++) if (x >= L.ranges[p][0] && x <= L.ranges[p][1]) return p;
    return null;
  }

  /** Client position of a 3D point in the 3D view, or null when hidden. */
  worldToClient3(xyz) {
    const v = this.viewports()['3d'];
    if (!v) return null;
    const r = this.canvas.getBoundingClientRect();
    const p = new THREE.Vector3(...xyz).project(this.cam3);
    return { x: r.left + v.x + ((p.x + 1) / 2) * v.w, y: r.top + v.y + ((1 - p.y) / 2) * v.h };
  }

  /** Page (client) coordinates of a world point of the 2D view, or null if the 2D view is hidden. */
  worldToClient2(x, y) {
    const v = this.viewports()['2d'];
    if (!v) return null;
    const r = this.canvas.getBoundingClientRect();
    const p = new THREE.Vector3(x, y, 0).project(this.cam2);
    return { x: r.left + v.x + ((p.x + 1) / 2) * v.w, y: r.top + v.y + ((1 - p.y) / 2) * v.h };
  }

  /** The point of the z = 0 plane under a client position in the 2D view (raycast). */
  clientToWorld2(clientX, clientY) {
    const v = this.viewports()['2d'];
    const r = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - r.left - v.x) / v.w) * 2 - 1, -((clientY - r.top - v.y) / v.h) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.cam2);
    const hit = new THREE.Vector3();
    ray.ray.intersectPlane(new THREE.Plane(new THREE.Vector3(0, 0, 1), 0), hit);
    return [hit.x, hit.y];
  }

  #viewportAt(clientX, clientY) {
    const r = this.canvas.getBoundingClientRect();
    const x = clientX - r.left, y = clientY - r.top;
    for (const [kind, v] of Object.entries(this.viewports())) {
      if (x >= v.x && x < v.x + v.w && y >= v.y && y < v.y + v.h) return kind;
    }
    return null;
  }

  #pickHandle3(clientX, clientY) {
    let best = null, bestD = HANDLE_PICK_PX;
    for (const h of this.handles3) {
      const c = this.worldToClient3(h.xyz);
      const d = c ? Math.hypot(c.x - clientX, c.y - clientY) : Infinity;
      if (d <= bestD) { bestD = d; best = h; }
    }
    return best;
  }

  #pickHandle(clientX, clientY) {
    let best = null, bestD = HANDLE_PICK_PX;
    for (const h of this.handles) {
      const c = this.worldToClient2(h.x, h.y);
      const d = Math.hypot(c.x - clientX, c.y - clientY);
      if (d <= bestD) { bestD = d; best = h; }
    }
    return best;
  }

  #installPointer() {
    const el = this.canvas;
    let drag = null;  // { kind: 'handle'|'pan', ... }
    // Decide who gets the event before OrbitControls sees it (registered earlier = runs first).
    const route = (e) => { this.controls && (this.controls.enabled = this.#viewportAt(e.clientX, e.clientY) === '3d' && !drag); };
    el.addEventListener('pointerdown', (e) => {
      route(e);
      el.focus({ preventScroll: true });  // for the Delete key
      if (e.button !== 0) return;
      const where = this.#viewportAt(e.clientX, e.clientY);
      if (where === '3d') {
        // On a surface: place an armed source, or drag a source handle over the surface.
        const h3 = this.showSources ? this.#pickHandle3(e.clientX, e.clientY) : null;
        if (this.placing) drag = { kind: 'place', x: e.clientX, y: e.clientY, view: '3d' };
        else if (h3) {
          drag = { kind: 'handle3', h: h3 };
          this.dragView = '3d';
          this.hooks.onSelect?.(h3.source);
          const hp = this.handles.find((x) => x.source === h3.source && x.key === h3.key);
          this.hooks.onDrag?.(h3.source, h3.key, hp ? [hp.x - this.sourceShift(), hp.y] : [0, 0], 'start');
        } else return;
        el.setPointerCapture(e.pointerId);
        if (this.controls) this.controls.enabled = false;
        return;
      }
      if (where !== '2d') return;
      const h = this.showSources ? this.#pickHandle(e.clientX, e.clientY) : null;
      el.setPointerCapture(e.pointerId);
      if (this.placing) {
        drag = { kind: 'place', x: e.clientX, y: e.clientY, view: '2d' };
      } else if (h) {
        drag = { kind: 'handle', h };
        this.hooks.onSelect?.(h.source);
        this.hooks.onDrag?.(h.source, h.key, [h.x - this.sourceShift(), h.y], 'start');
      } else {
        drag = { kind: 'pan', x: e.clientX, y: e.clientY, cx: this.view2.cx, cy: this.view2.cy };
      }
      if (this.controls) this.controls.enabled = false;
    });
    el.addEventListener('pointermove', (e) => {
      if (!drag) {
        const over = this.#viewportAt(e.clientX, e.clientY) === '2d' && this.showSources && this.#pickHandle(e.clientX, e.clientY);
        el.style.cursor = over ? 'grab' : '';
        return;
      }
      if (drag.kind === 'place') return;
      if (drag.kind === 'handle3') {
        el.style.cursor = 'grabbing';
        const hit = this.pick3D(e.clientX, e.clientY);
        if (hit && hit.patch === this.sourcePatch) this.hooks.onDrag?.(drag.h.source, drag.h.key, hit.uv, 'move');
        return;
      }
      if (drag.kind === 'handle') {
        el.style.cursor = 'grabbing';
        const [x, y] = this.clientToWorld2(e.clientX, e.clientY);
        this.hooks.onDrag?.(drag.h.source, drag.h.key, [x - this.sourceShift(), y], 'move');
      } else {
        const px = this.pixelSize2();
        this.view2.cx = drag.cx - (e.clientX - drag.x) * px;
        this.view2.cy = drag.cy + (e.clientY - drag.y) * px;
        this.#updateCam2();
        this.requestRender('2d');
      }
    });
    const end = (e) => {
      if (!drag) return;
      if (drag.kind === 'place') {
        // A click (not a drag) places the armed source where it hit.
        if (Math.hypot(e.clientX - drag.x, e.clientY - drag.y) < 6) {
          let hit = null;
          if (drag.view === '3d') hit = this.pick3D(e.clientX, e.clientY);
          else {
            const [x, y] = this.clientToWorld2(e.clientX, e.clientY);
            const patch = this.patchAt2(x);
            if (patch !== null) hit = { patch, uv: [x - (this.layout?.shift[patch] ?? 0), y] };
          }
          if (hit) this.hooks.onPlace?.(hit);
        }
      } else if (drag.kind === 'handle3') {
        this.dragView = null;
        const hit = this.pick3D(e.clientX, e.clientY);
        const hp = this.handles.find((x) => x.source === drag.h.source && x.key === drag.h.key);
        const uv = hit && hit.patch === this.sourcePatch ? hit.uv : hp ? [hp.x - this.sourceShift(), hp.y] : [0, 0];
        this.hooks.onDrag?.(drag.h.source, drag.h.key, uv, 'end');
      } else if (drag.kind === 'handle') {
        const [x, y] = this.clientToWorld2(e.clientX, e.clientY);
        this.hooks.onDrag?.(drag.h.source, drag.h.key, [x - this.sourceShift(), y], 'end');
      } else this.#refreshSources();  // dashed guides depend on the zoom
      drag = null;
      el.style.cursor = '';
    };
    el.addEventListener('pointerup', end);
    el.addEventListener('pointercancel', end);
    el.addEventListener('wheel', (e) => {
      route(e);
      if (this.#viewportAt(e.clientX, e.clientY) !== '2d') return;
      e.preventDefault();
      // Zoom about the cursor: the world point under it stays put.
      const [wx, wy] = this.clientToWorld2(e.clientX, e.clientY);
      const f = Math.exp(Math.sign(e.deltaY) * Math.min(Math.abs(e.deltaY), 200) * 0.0015);
      this.view2.halfH *= f;
      this.view2.cx = wx + (this.view2.cx - wx) * f;
      this.view2.cy = wy + (this.view2.cy - wy) * f;
      this.#updateCam2();
      this.#refreshSources();
    }, { passive: false });
    el.addEventListener('dblclick', (e) => {
      if (this.#viewportAt(e.clientX, e.clientY) === '2d') this.fit2D(this.meshBounds2());
      else this.fit3D();
    });
  }

  // --- test and measurement helpers ----------------------------------------------------

  /** Fraction of pixels of a viewport ('2d', '3d' or all) that differ from the background. */
  coverage(which = null) {
    this.requestRender();
    this.render();
    const src = this.canvas;
    const c = document.createElement('canvas');
    c.width = src.width; c.height = src.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0);
    const ratio = src.width / this.container.clientWidth;
    const v = which ? this.viewports()[which] : { x: 0, y: 0, w: this.container.clientWidth, h: this.container.clientHeight };
    if (!v) return 0;
    const data = ctx.getImageData(Math.round(v.x * ratio), Math.round(v.y * ratio), Math.max(1, Math.round(v.w * ratio)), Math.max(1, Math.round(v.h * ratio))).data;
    let differing = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - 0xf7) + Math.abs(data[i + 1] - 0xf7) + Math.abs(data[i + 2] - 0xf5) > 24) differing++;
    }
    return differing / (data.length / 4);
  }

  /** Orbits the 3D camera for ms milliseconds, rendering every animation frame; resolves to frames per second. */
  benchOrbit(ms = 3000) {
    return new Promise((resolve) => {
      const t0 = performance.now();
      let frames = 0;
      this.controls.autoRotate = true;
      this.controls.autoRotateSpeed = 30;
      this.#interacting(true);  // as while dragging with the mouse
      const tick = () => {
        this.controls.update(1 / 60);
        this.dirty = new Set(['3d']);
        this.render();
        frames++;
        const dt = performance.now() - t0;
        if (dt < ms) requestAnimationFrame(tick);
        else {
          this.controls.autoRotate = false;
          this.#interacting(false);
          resolve((frames * 1000) / dt);
        }
      };
      requestAnimationFrame(tick);
    });
  }
}

// --- geometry builders ------------------------------------------------------------------

// Colour tables: the colour maps sampled finely, so a mesh's colours are table look-ups.
const LUT = 1024;
function table(fn) {
  const t = new Float32Array(3 * (LUT + 1));
  for (let i = 0; i <= LUT; i++) t.set(fn(i / LUT), 3 * i);
  return t;
}
const qualityLut = table(qualityColor);
const lengthLut = table((x) => lengthColor(2 ** (2 * x - 1)));  // x = 0.5 + 0.5 log2(length)
const lutIndex = (x) => 3 * Math.round(LUT * (x < 0 ? 0 : x > 1 ? 1 : x));
// The edges' colours by row (web/wireframe.js): the length colours, then the plain one.
const PLAIN_EDGE_ROW = LUT + 1;
const edgeTable = new Float32Array(3 * (LUT + 2));
edgeTable.set(lengthLut);
edgeTable.set([0.25, 0.3, 0.38], 3 * PLAIN_EDGE_ROW);

// Colour of each face vertex (triangles, then quads as two triangles): quality colours or plain.
function fillFaceColors(out, mesh, quality, field = null) {
  const nt = mesh.triangles.length / 3, nq = mesh.quads.length / 4;
  let o = 0;
  const put = (r, g, b, times) => { for (let k = 0; k < times; k++) { out[o++] = r; out[o++] = g; out[o++] = b; } };
  let lo = Infinity, hi = -Infinity;
  if (field) for (let i = 0; i < field.length; i++) { lo = Math.min(lo, field[i]); hi = Math.max(hi, field[i]); }
  const span = hi > lo ? hi - lo : 1;
  // An element's field colour: the mean of its corners' values, scaled to the field's range.
  const shade = (vs) => {
    let sum = 0;
    for (const v of vs) sum += field[v];
    return fieldColor((sum / vs.length - lo) / span);
  };
  for (let e = 0; e < nt + nq; e++) {
    const times = e < nt ? 3 : 6;
    if (field) {
      const vs = e < nt ? mesh.triangles.subarray(3 * e, 3 * e + 3) : mesh.quads.subarray(4 * (e - nt), 4 * (e - nt) + 4);
      const c = shade(vs);
      put(c[0], c[1], c[2], times);
    } else if (quality) {
      const i = lutIndex(quality[e]);
      put(qualityLut[i], qualityLut[i + 1], qualityLut[i + 2], times);
    } else put(FACE_PLAIN[0], FACE_PLAIN[1], FACE_PLAIN[2], times);
  }
}

// Non-indexed triangles (quads split in two) so each element carries its own flat colour.
function fillFaces(pos, mesh, xyz) {
  const tris = mesh.triangles, quads = mesh.quads;
  let o = 0;
  const put = (v) => { pos[o++] = xyz[3 * v]; pos[o++] = xyz[3 * v + 1]; pos[o++] = xyz[3 * v + 2]; };
  for (let t = 0; t < tris.length; t++) put(tris[t]);
  for (let q = 0; q < quads.length; q += 4) {
    put(quads[q]); put(quads[q + 1]); put(quads[q + 2]);
    put(quads[q]); put(quads[q + 2]); put(quads[q + 3]);
  }
}

// The 2D layout of a mesh of several surface patches: every element corner at its (u, v)
// in its own patch (the core's cornerParams), patch p shifted along u by shift[p] so the
// patches sit side by side, never overlapping. boundary: corner indices in pairs (the
// patch's edges used by one element of the patch: its contour).
// Null for planar meshes and single patches (drawn from the vertex parameters).
function patchLayout(mesh, patches) {
  if (!patches?.element || !patches.corners) return null;
  const elem = patches.element, corners = patches.corners;
  let np = 0;
  for (const p of elem) np = Math.max(np, p + 1);
  if (np < 2) return null;
  const nt = mesh.triangles.length / 3, nq = mesh.quads.length / 4;
  const lo = new Float64Array(np).fill(Infinity), hi = new Float64Array(np).fill(-Infinity);
  let vlo = Infinity, vhi = -Infinity;
  const start = (e) => (e < nt ? 3 * e : 3 * nt + 4 * (e - nt));
  const arity = (e) => (e < nt ? 3 : 4);
  for (let e = 0; e < nt + nq; e++) {
    const p = elem[e];
    for (let k = 0; k < arity(e); k++) {
      const c = start(e) + k, u = corners[2 * c], v = corners[2 * c + 1];
      if (u < lo[p]) lo[p] = u;
      if (u > hi[p]) hi[p] = u;
      if (v < vlo) vlo = v;
      if (v > vhi) vhi = v;
    }
  }
  let width = 0;
  for (let p = 0; p < np; p++) if (hi[p] > lo[p]) width = Math.max(width, hi[p] - lo[p]);
  const gap = 0.12 * Math.max(width, vhi - vlo);
  const shift = new Float64Array(np);
  const ranges = [];
  let x = 0;
  for (let p = 0; p < np; p++) {
    ranges.push([x, x + Math.max(0, hi[p] - lo[p])]);
    if (!(hi[p] >= lo[p])) continue;
    shift[p] = x - lo[p];
    x += hi[p] - lo[p] + gap;
  }
  const ncorner = 3 * nt + 4 * nq;
  const uv = new Float32Array(3 * ncorner);
  for (let e = 0; e < nt + nq; e++) {
    for (let k = 0; k < arity(e); k++) {
      const c = start(e) + k;
      uv[3 * c] = corners[2 * c] + shift[elem[e]]; uv[3 * c + 1] = corners[2 * c + 1];
    }
  }
  // Edges per patch, keyed by (patch, vertex pair); the count tells the contour edges.
  const verts = mesh.triangles, quads = mesh.quads, nv = mesh.params.length / 2;
  const seen = new Map();
  const edges = [], boundary = [];
  for (let e = 0; e < nt + nq; e++) {
    const n = arity(e), s0 = start(e);
    for (let k = 0; k < n; k++) {
      const a = e < nt ? verts[3 * e + k] : quads[4 * (e - nt) + k];
      const b = e < nt ? verts[3 * e + ((k + 1) % 3)] : quads[4 * (e - nt) + ((k + 1) % 4)];
      const key = (elem[e] * nv + Math.min(a, b)) * nv + Math.max(a, b);
      const hit = seen.get(key);
      if (hit === undefined) {
        seen.set(key, edges.length);
        edges.push(s0 + k, s0 + ((k + 1) % n));
      } else seen.set(key, -1);
    }
  }
  for (const i of seen.values()) if (i >= 0) boundary.push(edges[i], edges[i + 1]);
  return {
    uv, shift, ranges, boundary: Uint32Array.from(boundary),
    bounds: [0, vlo, Math.max(x - gap, 1e-9), vhi],
  };
}

// Non-indexed faces of a laid-out surface mesh: corner c of the elements at xyz[3 c].
function fillFacesLaidOut(pos, mesh, layout) {
  const nt = mesh.triangles.length / 3, nq = mesh.quads.length / 4, uv = layout.uv;
  let o = 0;
  const put = (c) => { pos[o++] = uv[3 * c]; pos[o++] = uv[3 * c + 1]; pos[o++] = 0; };
  for (let c = 0; c < 3 * nt; c++) put(c);
  for (let q = 0; q < nq; q++) {
    const c = 3 * nt + 4 * q;
    put(c); put(c + 1); put(c + 2);
    put(c); put(c + 2); put(c + 3);
  }
}

// Line segments (pairs of vertex ids) as non-indexed positions.
function fillSegments(pos, pairs, xyz) {
  const n = pairs ? pairs.length : 0;
  for (let i = 0; i < n; i++) {
    const v = pairs[i];
    pos[3 * i] = xyz[3 * v]; pos[3 * i + 1] = xyz[3 * v + 1]; pos[3 * i + 2] = xyz[3 * v + 2];
  }
}

function boundsOf(xyz, n) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      const x = xyz[3 * i + k];
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
  }
  return n ? new THREE.Box3(new THREE.Vector3(...lo), new THREE.Vector3(...hi)) : new THREE.Box3();
}

/** True when WebGL runs on a software rasterizer (SwiftShader, llvmpipe): MSAA is then too costly. */
export function softwareWebGL() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2') ?? document.createElement('canvas').getContext('webgl');
    if (!gl) return false;
    const ext = gl.getExtension('WEBGL_debug_renderer_info');
    const name = ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|softpipe|software/i.test(String(name));
  } catch {
    return false;
  }
}
