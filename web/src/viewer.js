// The 3D view: one shaded mesh plus overlays that share its position
// attribute (wireframe, selected faces, vanish mask), so a positions-only
// frame updates every layer with a single upload. Rendering happens only
// when something changed (frames, camera moves, overlays); on a software
// rasterizer a stroke frame redraws only the rectangle it changed (see
// renderPartial and README.md).

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { applySparse, applyPatch, isCommit } from './frame.js';
import { vertexTriangles, indexRuns, clusterDecimate, areaNormals } from './proxy.js';

/** Meshes above this many triangles are drawn as a decimated proxy while the
 * camera moves (and the full mesh again when it stops). */
export const PROXY_ABOVE = 300000;
/** Proxy size. A software rasterizer (SwiftShader, llvmpipe) pays so much
 * per triangle and pixel that 120k triangles make ~20 fps at best there;
 * 60k at 0.35 resolution make ~30 fps (see web/e2e perf.json). */
const PROXY_TARGET = 120000;
const PROXY_TARGET_SOFTWARE = 60000;
/** Pixel ratio while the camera moves or a stroke runs, as a share of the
 * resting one (software rasterizers pay per pixel). */
const MOTION_SCALE_SOFTWARE = 0.35;
/** How long the camera must be still before the full picture comes back. */
const SETTLE_MS = 180;

const BASE_COLOR = 0xb9c3d3;
/** A partial redraw whose rectangle covers more than this share of the
 * picture is done as a full one. */
const PARTIAL_MAX_AREA = 0.6;
/** Margin (drawing-buffer pixels) around a damaged rectangle: rounding of the
 * CPU projection versus the rasterizer, and 1-pixel lines. */
const DAMAGE_MARGIN = 3;

/** Is WebGL drawn by the CPU (SwiftShader, llvmpipe)? Asked on a throwaway
 * context because antialiasing cannot be changed after creation. */
function isSoftwareGL() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return false;
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|softpipe|software/i.test(String(name));
  } catch {
    return false;
  }
}

export class Viewer {
  constructor(canvas) {
    this.canvas = canvas;
    this.software = isSoftwareGL();
    // Throws if WebGL is unavailable; main.js turns that into a message.
    // A software rasterizer spends ~2.5× longer per picture with MSAA, so
    // there we trade smooth edges for a usable frame rate.
    // Partial redraws (during a stroke only the screen rectangle the brush
    // changed is drawn again, over the previous picture) need the drawing
    // buffer kept between pictures. Only where drawing is expensive per
    // triangle: a software rasterizer.
    this.partialEnabled = this.software;
    this.renderer = new THREE.WebGLRenderer({
      canvas, antialias: !this.software, powerPreference: 'high-performance',
      preserveDrawingBuffer: this.partialEnabled,
    });
    this.restPixelRatio = this.software ? 1 : Math.min(window.devicePixelRatio || 1, 2);
    this.motionPixelRatio = this.software ? this.restPixelRatio * MOTION_SCALE_SOFTWARE : Math.min(this.restPixelRatio, 1);
    this.renderer.setPixelRatio(this.restPixelRatio);
    this.renderer.setClearColor(0x1d2230);

    this.scene = new THREE.Scene();
    this.perspCamera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    // The orthographic camera's frustum is a half height (orthoHalf) times
    // the aspect; OrbitControls zoom it through `zoom`.
    this.orthoCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.01, 1000);
    this.orthoHalf = 1;
    this.camera = this.perspCamera;
    this.camera.position.set(0, 0, 5);
    this.scene.add(this.perspCamera, this.orthoCamera);
    // Light rides with the camera: whatever side the artist orbits to is lit.
    const key = new THREE.DirectionalLight(0xffffff, 2.2);
    key.position.set(0.4, 0.8, 1);
    this.key = key;
    this.camera.add(key);
    this.scene.add(new THREE.HemisphereLight(0xdde6ff, 0x303040, 1.1));

    this.materialName = 'studio';
    this.material = makeMaterial('studio', false);
    this.wireMaterial = new THREE.LineBasicMaterial({ color: 0x1a1f2b, transparent: true, opacity: 0.55 });
    this.selMaterial = new THREE.MeshBasicMaterial({
      color: 0xff9a2e, transparent: true, opacity: 0.6, side: THREE.DoubleSide, depthWrite: false,
    });
    this.maskMaterial = new THREE.MeshBasicMaterial({
      color: 0xff2a2a, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthTest: false, depthWrite: false,
    });


    this.mesh = null; // THREE.Mesh of the current frame
    this.wire = null;
    this.selMesh = null;
    this.maskMesh = null;
    // The sculpt mask: a Uint8Array per vertex (1 = masked), or null. It is
    // drawn through the mesh's own 'masked' attribute: the material
    // darkens masked vertices' shading (see makeMaterial), so the masked
    // part keeps its shape on screen and its rim fades over one triangle.
    this.sculptMask = null;
    this.frame = null;
    this.flat = false;
    this.showWire = true;
    this.bbox = { min: [0, 0, 0], max: [0, 0, 0], center: [0, 0, 0], diag: 1 };

    this.cornerPoints = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ color: 0x3dffb0, size: 11, sizeAttenuation: false, depthTest: false }),
    );
    this.cornerPoints.renderOrder = 10;
    this.cornerPoints.frustumCulled = false;
    this.edgeLine = new THREE.LineSegments(
      new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ color: 0x3dffb0, depthTest: false }),
    );
    this.edgeLine.renderOrder = 10;
    this.edgeLine.frustumCulled = false;
    this.scene.add(this.cornerPoints, this.edgeLine);

    const ring = new Float32Array(64 * 3);
    for (let i = 0; i < 64; i++) {
      const a = (i / 64) * Math.PI * 2;
      ring[3 * i] = Math.cos(a);
      ring[3 * i + 1] = Math.sin(a);
    }
    const ringGeo = new THREE.BufferGeometry();
    ringGeo.setAttribute('position', new THREE.BufferAttribute(ring, 3));
    this.brush = new THREE.LineLoop(ringGeo, new THREE.LineBasicMaterial({ color: 0xffe066, depthTest: false }));
    this.brush.renderOrder = 11;
    this.brush.visible = false;
    this.scene.add(this.brush);

    this.controls = null; // created by attachControls() after the app's own pointer handlers
    this.renders = 0;
    this.lastRenderAt = 0;
    this.pendingRender = 0;
    this.afterRender = null; // optional callback(renderStart, renderEnd), for measurements
    // Damage since the last picture: null (nothing), 'full', or a rectangle
    // in drawing-buffer pixels (GL convention, y up) {x0, y0, x1, y1}.
    this.damage = null;
    this.lastViewSig = ''; // camera + drawing buffer of the last picture
    this.partialRenders = 0;
    this.partialTriangles = 0; // triangles drawn by the last partial redraw
    this.forceFull = false; // tests: draw every picture in full
    // Screen positions (drawing-buffer pixels) of every vertex for the view
    // `screenSig`, kept current for moved vertices during a stroke.
    this.screen = null;
    this.screenSig = '';
    this.screenFor = null; // the position array they were projected from
    this.partMesh = null; // draws the triangles of a partial redraw
    this._m = new THREE.Matrix4();
    this._size = new THREE.Vector2();
    // Motion (orbit, zoom, stroke): lower resolution, proxy for huge meshes.
    this.motion = new Set(); // reasons the view is in motion: 'orbit', 'stroke', 'bench'
    this.settleTimer = 0;
    this.proxy = null; // THREE.Mesh of the decimated mesh, or null
    this.proxyFor = null; // the frame the proxy was built from
    this.proxyIdle = 0;
    this.proxyMs = null;
    this.useProxy = true;
    this.proxyTarget = this.software ? PROXY_TARGET_SOFTWARE : PROXY_TARGET;
    // Local normal updates: vertex → triangle adjacency and scratch arrays.
    this.adj = null;
    this.stamp = null;
    this.epoch = 0;
    this.touched = null;
    this._ray = new THREE.Raycaster();
    this._v = new THREE.Vector3();
    this._v2 = new THREE.Vector2();

    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
    this.resize();
  }

  /** OrbitControls listen on the canvas; attach them after our own pointerdown
   * handler so that a sculpt stroke can disable them before they react. */
  attachControls() {
    const c = new OrbitControls(this.camera, this.canvas);
    c.enableDamping = false; // damping would need a render loop running all the time
    c.zoomToCursor = true;
    // Left and right buttons orbit, the middle one pans (so does Shift or
    // Ctrl + drag on empty space), the wheel zooms: a right or middle drag
    // never starts an edit, and Shift-drag on the mesh is free to smooth.
    c.mouseButtons = { LEFT: THREE.MOUSE.ROTATE, MIDDLE: THREE.MOUSE.PAN, RIGHT: THREE.MOUSE.ROTATE };
    // Motion starts with the drag (or wheel); the full picture returns once
    // the camera has been still for SETTLE_MS (a wheel tick is start, change
    // and end at once, so 'end' alone cannot say the zooming is over).
    c.addEventListener('start', () => {
      clearTimeout(this.settleTimer);
      this.dragging = true;
      this.beginMotion('orbit');
    });
    c.addEventListener('change', () => {
      if (!this.dragging && !this.quietChange) {
        this.beginMotion('orbit');
        this.settleLater();
      }
      this.requestRender();
    });
    c.addEventListener('end', () => {
      this.dragging = false;
      this.settleLater();
    });
    this.controls = c;
  }

  resize() {
    const el = this.canvas.parentElement;
    const w = Math.max(1, el.clientWidth), h = Math.max(1, el.clientHeight);
    this.renderer.setSize(w, h, false);
    this.aspect = w / h;
    this.updateProjection();
    this.renderNow();
  }

  settleLater() {
    clearTimeout(this.settleTimer);
    this.settleTimer = setTimeout(() => {
      if (!this.dragging) this.endMotion('orbit');
    }, SETTLE_MS);
  }

  /** Enter a motion state: lower resolution and, for a huge mesh, the proxy. */
  beginMotion(reason) {
    if (this.motion.has(reason)) return;
    this.motion.add(reason);
    this.applyMotion();
  }

  endMotion(reason) {
    if (!this.motion.delete(reason)) return;
    this.applyMotion();
    if (!this.motion.size && !this.proxy) this.scheduleProxy();
  }

  applyMotion() {
    const moving = this.motion.size > 0;
    const ratio = moving ? this.motionPixelRatio : this.restPixelRatio;
    if (this.renderer.getPixelRatio() !== ratio) this.renderer.setPixelRatio(ratio);
    // Only camera motion swaps in the proxy: a stroke must show the real surface.
    const cameraMoving = this.motion.has('orbit') || this.motion.has('bench');
    this.setProxyVisible(cameraMoving && this.useProxy && this.frame && this.frame.nt > PROXY_ABOVE);
    this.requestRender();
  }

  setProxyVisible(on) {
    if (on) on = this.ensureProxy();
    if (this.proxy) this.proxy.visible = on;
    if (this.mesh) this.mesh.visible = !on;
    if (this.wire) this.wire.visible = this.showWire && !on;
    this.proxyShown = on;
  }

  /** Build (or reuse) the decimated stand-in of the current mesh. */
  ensureProxy() {
    const f = this.frame;
    if (!f || !this.mesh) return false;
    if (this.proxy && this.proxyFor === f) return true;
    this.disposeProxy();
    const t0 = performance.now();
    const d = clusterDecimate(f.positions, f.tris, this.bbox, this.proxyTarget, this.sculptMask);
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(d.positions, 3));
    geo.setAttribute('normal', new THREE.BufferAttribute(d.normals, 3));
    if (d.masked) geo.setAttribute('masked', new THREE.BufferAttribute(d.masked, 1));
    geo.setIndex(new THREE.BufferAttribute(d.index, 1));
    this.proxy = new THREE.Mesh(geo, this.material);
    this.proxy.frustumCulled = false;
    this.proxy.visible = false;
    this.proxyFor = f;
    this.proxyTriangles = d.nt;
    this.proxyMs = performance.now() - t0;
    this.scene.add(this.proxy);
    return true;
  }

  disposeProxy() {
    cancelIdle(this.proxyIdle);
    this.proxyIdle = 0;
    if (!this.proxy) return;
    this.scene.remove(this.proxy);
    this.proxy.geometry.dispose();
    this.proxy = this.proxyFor = null;
    this.proxyShown = false;
  }

  /** A huge mesh arrived: build its proxy when the page is idle, so the
   * first orbit does not wait for it. */
  scheduleProxy() {
    if (!this.frame || this.frame.nt <= PROXY_ABOVE || !this.useProxy) return;
    cancelIdle(this.proxyIdle);
    this.proxyIdle = onIdle(() => {
      this.proxyIdle = 0;
      if (this.motion.size === 0) this.ensureProxy();
    });
  }

  /** Draw at the next animation frame. `rect` (drawing-buffer pixels) says
   * only that part of the picture changed; without it, everything. */
  requestRender(rect) {
    if (rect === undefined || rect === null) this.damage = 'full';
    else if (this.damage !== 'full') this.damage = unionRect(this.damage, rect);
    if (this.pendingRender) return;
    this.pendingRender = requestAnimationFrame(() => {
      this.pendingRender = 0;
      this.renderNow();
    });
  }

  renderNow() {
    if (this.pendingRender) {
      cancelAnimationFrame(this.pendingRender);
      this.pendingRender = 0;
    }
    const t0 = performance.now();
    const damage = this.damage;
    this.damage = null;
    this.camera.updateMatrixWorld();
    const sig = this.viewSig();
    let drawn = false;
    if (damage && damage !== 'full' && sig === this.lastViewSig && this.partialPossible(sig)) {
      drawn = this.renderPartial(damage);
    }
    if (!drawn) this.renderer.render(this.scene, this.camera);
    this.lastRenderPartial = drawn;
    this.lastViewSig = sig;
    this.renders++;
    this.lastRenderAt = performance.now();
    this.afterRender?.(t0, this.lastRenderAt);
  }

  // ---- partial redraws -----------------------------------------------------

  /** Camera and drawing buffer: a picture can be patched only over one drawn
   * with the same. */
  viewSig() {
    const c = this.camera;
    this.renderer.getDrawingBufferSize(this._size);
    return `${this._size.x}x${this._size.y}|${c.matrixWorld.elements.join(',')}|${c.projectionMatrix.elements.join(',')}`;
  }

  partialPossible(sig) {
    return this.partialEnabled && !this.forceFull && this.mesh && this.mesh.visible && !this.proxyShown
      && this.screen && this.screenSig === sig
      && this.screenFor === this.frame?.positions;
  }

  /** World → drawing-buffer pixels for the current camera (y up). */
  viewProjection() {
    const c = this.camera;
    c.updateMatrixWorld();
    return this._m.multiplyMatrices(c.projectionMatrix, c.matrixWorldInverse).elements;
  }

  /** Project every vertex (O(nv)); false if one is behind the camera. */
  projectAll() {
    const f = this.frame, p = f.positions, nv = f.nv;
    if (!this.screen || this.screen.length < 2 * nv) this.screen = new Float32Array(2 * nv);
    const e = this.viewProjection(), s = this.screen;
    this.renderer.getDrawingBufferSize(this._size);
    const W = this._size.x / 2, H = this._size.y / 2;
    let ok = true;
    for (let v = 0; v < nv; v++) {
      const x = p[3 * v], y = p[3 * v + 1], z = p[3 * v + 2];
      const w = e[3] * x + e[7] * y + e[11] * z + e[15];
      if (!(w > 0)) { ok = false; break; }
      s[2 * v] = ((e[0] * x + e[4] * y + e[8] * z + e[12]) / w + 1) * W;
      s[2 * v + 1] = ((e[1] * x + e[5] * y + e[9] * z + e[13]) / w + 1) * H;
    }
    this.screenSig = ok ? this.viewSig() : '';
    this.screenFor = ok ? p : null;
    return ok;
  }

  /** Re-project the given vertices; false if one is behind the camera. */
  projectSome(idx) {
    const p = this.frame.positions, s = this.screen, e = this.viewProjection();
    this.renderer.getDrawingBufferSize(this._size);
    const W = this._size.x / 2, H = this._size.y / 2;
    for (let i = 0; i < idx.length; i++) {
      const v = idx[i];
      const x = p[3 * v], y = p[3 * v + 1], z = p[3 * v + 2];
      const w = e[3] * x + e[7] * y + e[11] * z + e[15];
      if (!(w > 0)) return false;
      s[2 * v] = ((e[0] * x + e[4] * y + e[8] * z + e[12]) / w + 1) * W;
      s[2 * v + 1] = ((e[1] * x + e[5] * y + e[9] * z + e[13]) / w + 1) * H;
    }
    return true;
  }

  /** Screen bounds of the given vertices (from `screen`). */
  screenBounds(list, n, r = null) {
    const s = this.screen;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    if (r) ({ x0, y0, x1, y1 } = r);
    for (let i = 0; i < n; i++) {
      const v = list[i], x = s[2 * v], y = s[2 * v + 1];
      if (x < x0) x0 = x; if (x > x1) x1 = x;
      if (y < y0) y0 = y; if (y > y1) y1 = y;
    }
    return { x0, y0, x1, y1 };
  }

  /** Screen bounds of every triangle around the given vertices. */
  ringBounds(list, n, r) {
    const s = this.screen, { start, tri } = this.adj, t = this.frame.tris;
    let { x0, y0, x1, y1 } = r;
    for (let i = 0; i < n; i++) {
      const v = list[i];
      for (let j = start[v], end = start[v + 1]; j < end; j++) {
        const o = 3 * tri[j];
        for (let c = 0; c < 3; c++) {
          const w = 2 * t[o + c], x = s[w], y = s[w + 1];
          if (x < x0) x0 = x; if (x > x1) x1 = x;
          if (y < y0) y0 = y; if (y > y1) y1 = y;
        }
      }
    }
    return { x0, y0, x1, y1 };
  }

  /** Screen bounds of the brush ring where it is now (null: behind the camera). */
  brushBounds() {
    const b = this.brush;
    if (!b.visible) return { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
    b.updateMatrixWorld();
    this.camera.updateMatrixWorld();
    const m = this._m.multiplyMatrices(this.camera.projectionMatrix, this.camera.matrixWorldInverse)
      .multiply(b.matrixWorld).elements;
    this.renderer.getDrawingBufferSize(this._size);
    const W = this._size.x / 2, H = this._size.y / 2;
    const ring = b.geometry.attributes.position.array;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < ring.length; i += 3) {
      const x = ring[i], y = ring[i + 1];
      const w = m[3] * x + m[7] * y + m[15];
      if (!(w > 0)) return null;
      const sx = ((m[0] * x + m[4] * y + m[12]) / w + 1) * W, sy = ((m[1] * x + m[5] * y + m[13]) / w + 1) * H;
      if (sx < x0) x0 = sx; if (sx > x1) x1 = sx;
      if (sy < y0) y0 = sy; if (sy > y1) y1 = sy;
    }
    return { x0, y0, x1, y1 };
  }

  /** Draw the damaged rectangle again over the kept picture: scissor, clear,
   * and the triangles whose screen bounds meet it (in their original order,
   * so depth ties resolve as in a full picture); overlays are drawn whole
   * under the scissor. False when a full picture is the better deal. */
  renderPartial(r) {
    this.renderer.getDrawingBufferSize(this._size);
    const bw = this._size.x, bh = this._size.y;
    const x0 = Math.max(0, Math.floor(r.x0) - DAMAGE_MARGIN), y0 = Math.max(0, Math.floor(r.y0) - DAMAGE_MARGIN);
    const x1 = Math.min(bw, Math.ceil(r.x1) + DAMAGE_MARGIN), y1 = Math.min(bh, Math.ceil(r.y1) + DAMAGE_MARGIN);
    if (!(x1 > x0 && y1 > y0)) return true; // nothing on screen changed
    if ((x1 - x0) * (y1 - y0) > PARTIAL_MAX_AREA * bw * bh) return false;
    const f = this.frame, t = f.tris, s = this.screen, nt = f.nt;
    if (!this.partMesh || this.partMesh.userData.for !== this.mesh || this.partMesh.geometry.index.array.length < 3 * nt) this.makePartMesh();
    const idxAttr = this.partMesh.geometry.index, out = idxAttr.array;
    let k = 0;
    for (let i = 0; i < 3 * nt; i += 3) {
      const a = 2 * t[i], b = 2 * t[i + 1], c = 2 * t[i + 2];
      const ax = s[a], bx = s[b], cx = s[c];
      if ((ax < x0 && bx < x0 && cx < x0) || (ax > x1 && bx > x1 && cx > x1)) continue;
      const ay = s[a + 1], by = s[b + 1], cy = s[c + 1];
      if ((ay < y0 && by < y0 && cy < y0) || (ay > y1 && by > y1 && cy > y1)) continue;
      out[k++] = t[i]; out[k++] = t[i + 1]; out[k++] = t[i + 2];
    }
    if (k > 0) {
      idxAttr.clearUpdateRanges();
      idxAttr.addUpdateRange(0, k);
      idxAttr.needsUpdate = true;
    }
    this.partMesh.geometry.setDrawRange(0, k);
    const pr = this.renderer.getPixelRatio();
    this.renderer.setScissor(x0 / pr, y0 / pr, (x1 - x0) / pr, (y1 - y0) / pr);
    this.renderer.setScissorTest(true);
    this.mesh.visible = false;
    this.partMesh.visible = true;
    try {
      this.renderer.render(this.scene, this.camera);
    } finally {
      this.mesh.visible = true;
      this.partMesh.visible = false;
      this.renderer.setScissorTest(false);
    }
    this.partialRenders++;
    this.partialTriangles = k / 3;
    this.lastPartialRect = [x0, y0, x1, y1];
    return true;
  }

  /** A mesh sharing the shown mesh's attributes, with its own index. */
  makePartMesh() {
    this.disposePartMesh();
    const g = this.mesh.geometry;
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', g.attributes.position);
    geo.setAttribute('normal', g.attributes.normal);
    geo.setAttribute('masked', g.attributes.masked);
    geo.setIndex(new THREE.BufferAttribute(new Uint32Array(Math.max(3, g.index.array.length)), 1));
    geo.setDrawRange(0, 0);
    this.partMesh = new THREE.Mesh(geo, this.material);
    this.partMesh.frustumCulled = false;
    this.partMesh.visible = false;
    this.partMesh.userData.for = this.mesh;
    this.scene.add(this.partMesh);
  }

  disposePartMesh() {
    if (!this.partMesh) return;
    this.scene.remove(this.partMesh);
    // Only the index is its own; position and normal belong to the mesh
    // (disposing a geometry frees the GL buffers of all its attributes).
    const g = this.partMesh.geometry;
    g.deleteAttribute('position');
    g.deleteAttribute('normal');
    g.dispose();
    this.partMesh = null;
  }

  // ---- frames -------------------------------------------------------------

  /** Show a parsed frame. Returns true when connectivity changed. */
  setFrame(f) {
    const prev = this.frame;
    if (f.patch) return this.setPatch(f, prev);
    this.frame = f;
    if (f.positionsOnly && this.mesh && prev && prev.nv === f.nv) {
      if (isCommit(f)) {
        // A commit frame (PROTOCOL.md): what is on screen is the
        // document's mesh now. Nothing moved; a drag's vanish tint goes
        // (the only thing to draw), and what a whole frame would have
        // settled is settled: the bounds the stroke moved (the view's
        // fit, the brush's size) and the stand-in for orbiting.
        f.positions = prev.positions;
        if (this.maskShown) {
          this.keepMask(null);
          this.updateMask();
          this.requestRender();
        }
        this.computeBounds();
        this.scheduleProxy();
        return false;
      }
      if (this.proxy) this.disposeProxy(); // the surface moved
      const attr = this.mesh.geometry.attributes.position;
      if (f.sparse) {
        // The frame still points at the array on screen (see parseFrame).
        // A frame moving a large part of the mesh is drawn whole.
        let damage = this.partialEnabled && !this.forceFull && f.sparseIdx.length <= f.nv / 4
          ? this.oldDamage(f.sparseIdx) : null;
        applySparse(attr.array, f.sparseIdx, f.sparsePos);
        f.positions = prev.positions;
        const moved = this.touchedVertices(f.sparseIdx, false);
        markRanges(attr, moved.list, moved.n, 3);
        let ring = null;
        if (!this.flat) ring = this.updateNormalsAround(f.sparseIdx);
        if (damage) {
          if (!this.projectSome(f.sparseIdx)) damage = null;
          else {
            if (!ring) ring = this.touchedVertices(f.sparseIdx, true);
            damage = this.ringBounds(ring.list, ring.n, damage);
            // Triangles entering or leaving the vanish mask (grab/move).
            const ch = this.maskChanges(f.mask);
            if (ch) damage = this.ringBounds(ch.list, ch.n, damage);
            else damage = null;
          }
        }
        this.keepMask(f.mask);
        if (!damage) this.screenFor = null; // projected positions are stale
        this.updateMask();
        this.requestRender(damage);
      } else {
        attr.array.set(f.positions);
        markWhole(attr);
        // Keep the frame pointing at the live arrays so picking sees them.
        f.positions = prev.positions;
        if (!this.flat) this.updateNormals();
        this.screenFor = null;
        this.keepMask(f.mask);
        this.updateMask();
        this.requestRender();
      }
      return false;
    }
    if (f.sparse) throw new Error('a sparse frame needs the previous mesh on screen');
    this.screenFor = null;
    this.keepMask(f.mask);
    this.requestRender();
    // A triangle display (the sculpt workspace) may next come as patches
    // that add vertices and triangles: its arrays get room to grow into.
    const roomy = f.nf === f.nt && f.nt > 0;
    const copy = (Type, a, size, n) => {
      if (!roomy) return a;
      const out = new Type(size * (Math.ceil(1.25 * n) + 1024));
      out.set(a);
      return out;
    };
    const store = {
      positions: copy(Float32Array, f.positions, 3, f.nv), tris: copy(Uint32Array, f.tris, 3, f.nt),
      triFace: copy(Uint32Array, f.triFace, 1, f.nt), edges: copy(Uint32Array, f.edges, 2, f.ne),
    };
    f.positions = store.positions.subarray(0, 3 * f.nv);
    f.tris = store.tris.subarray(0, 3 * f.nt);
    f.triFace = store.triFace.subarray(0, f.nt);
    f.edges = store.edges.subarray(0, 2 * f.ne);
    this.buildMesh(f, store);
    this.setSculptMask(f.sculptMask);
    return true;
  }

  /** The mesh objects of frame `f` over the arrays `store` holds its views
   * in (each possibly longer: room for patches). */
  buildMesh(f, store) {
    this.disposeMesh();
    this.disposeProxy();
    this.adj = null;
    this.store = store;
    const cap = store.positions.length / 3;
    const pos = liveAttribute(store.positions, 3);
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', pos);
    geo.setAttribute('normal', liveAttribute(new Float32Array(3 * cap), 3));
    geo.setAttribute('masked', liveAttribute(new Float32Array(cap), 1));
    geo.setIndex(liveAttribute(store.tris, 1));
    geo.setDrawRange(0, 3 * f.nt);
    this.mesh = new THREE.Mesh(geo, this.material);
    // Bounds are tracked by hand (computeBoundingSphere would allocate); the
    // whole mesh is always on screen anyway.
    this.mesh.frustumCulled = false;
    if (!this.flat) this.updateNormals();

    const wgeo = new THREE.BufferGeometry();
    wgeo.setAttribute('position', pos);
    wgeo.setIndex(liveAttribute(store.edges, 1));
    wgeo.setDrawRange(0, 2 * f.ne);
    this.wire = new THREE.LineSegments(wgeo, this.wireMaterial);
    this.wire.frustumCulled = false;
    this.wire.visible = this.showWire;

    const sgeo = new THREE.BufferGeometry();
    sgeo.setAttribute('position', pos);
    this.selMesh = new THREE.Mesh(sgeo, this.selMaterial);
    this.selMesh.frustumCulled = false;
    this.selMesh.visible = false;
    this.selMesh.renderOrder = 2;

    const mgeo = new THREE.BufferGeometry();
    mgeo.setAttribute('position', pos);
    mgeo.setIndex(new THREE.BufferAttribute(new Uint32Array(Math.max(3, store.tris.length)), 1));
    this.maskMesh = new THREE.Mesh(mgeo, this.maskMaterial);
    this.maskMesh.frustumCulled = false;
    this.maskMesh.visible = false;
    this.maskMesh.renderOrder = 3;

    this.scene.add(this.mesh, this.wire, this.selMesh, this.maskMesh);
    this.computeBounds();
    this.updateMask();
    if (this.motion.size) this.applyMotion();
    this.scheduleProxy();
  }

  /** A connectivity patch (PROTOCOL.md, bit 5) over the mesh on screen: the
   * changed slots are written into the arrays in place, only their ranges
   * go to the GPU, normals are computed again around them, and the picture
   * is redrawn over the old and new screen bounds of what changed. Arrays
   * without room for the new counts are replaced, and the mesh built again. */
  setPatch(f, prev) {
    const p = f.patch;
    if (!this.mesh || !this.store || !prev || prev.nv !== p.from[0] || prev.nt !== p.from[1] || prev.ne !== p.from[2]) {
      throw new Error('a patch frame needs the previous mesh on screen');
    }
    if (this.proxy) this.disposeProxy(); // the surface changed
    // The vertices whose triangles change: the corners, old and new, of
    // the changed slots, and those of the slots dropped.
    const t0 = prev.tris, nOld = p.tIdx.length + Math.max(0, prev.nt - f.nt);
    const seeds = new Uint32Array(p.vIdx.length + 3 * p.tIdx.length + 3 * nOld);
    let ns = 0;
    seeds.set(p.vIdx, 0);
    ns = p.vIdx.length;
    seeds.set(p.tVerts, ns);
    ns += p.tVerts.length;
    const oldStart = ns;
    for (let i = 0; i < p.tIdx.length; i++) {
      const t = p.tIdx[i];
      if (t < prev.nt) for (let c = 0; c < 3; c++) seeds[ns++] = t0[3 * t + c];
    }
    for (let t = f.nt; t < prev.nt; t++) for (let c = 0; c < 3; c++) seeds[ns++] = t0[3 * t + c];
    // The old bounds: listed vertices where they were, and old corners.
    let damage = null;
    if (this.partialEnabled && !this.forceFull && p.tIdx.length <= f.nt / 4 && p.vIdx.length <= f.nv / 4) {
      let k = 0;
      while (k < p.vIdx.length && p.vIdx[k] < prev.nv) k++;
      damage = this.oldDamage(p.vIdx.subarray(0, k));
      if (damage) damage = this.screenBounds(seeds.subarray(oldStart, ns), ns - oldStart, damage);
    }
    // Old corners gone beyond the new vertex count need no normals.
    let nSeeds = oldStart;
    for (let i = oldStart; i < ns; i++) if (seeds[i] < f.nv) seeds[nSeeds++] = seeds[i];
    const g = this.mesh.geometry, posAttr = g.attributes.position, idxAttr = g.index, wireIdx = this.wire.geometry.index;
    const out = applyPatch(f, this.store);
    this.store = out;
    this.frame = f;
    this.adj = null;
    const maskAttr = g.attributes.masked;
    if (this.sculptMask || p.vMask) {
      let m = this.sculptMask;
      if (!m || m.length !== f.nv) {
        m = new Uint8Array(f.nv);
        if (this.sculptMask) m.set(this.sculptMask.subarray(0, Math.min(f.nv, this.sculptMask.length)));
      }
      for (let i = 0; i < p.vIdx.length; i++) m[p.vIdx[i]] = p.vMask ? p.vMask[i] : 0;
      this.sculptMask = m;
    }
    this.keepMask(null);
    if (out.positions !== posAttr.array || out.tris !== idxAttr.array || out.edges !== wireIdx.array) {
      // No room left in the GPU's buffers: built again around the new arrays.
      this.screenFor = null;
      this.requestRender();
      this.buildMesh(f, out);
      this.updateSculptMask();
      return false;
    }
    markRanges(posAttr, p.vIdx, p.vIdx.length, 3);
    markRanges(idxAttr, p.tIdx, p.tIdx.length, 3);
    markRanges(wireIdx, p.eIdx, p.eIdx.length, 2);
    g.setDrawRange(0, 3 * f.nt);
    this.wire.geometry.setDrawRange(0, 2 * f.ne);
    if (this.sculptMask) {
      const a = maskAttr.array, m = this.sculptMask;
      for (let i = 0; i < p.vIdx.length; i++) a[p.vIdx[i]] = m[p.vIdx[i]];
      markRanges(maskAttr, p.vIdx, p.vIdx.length, 1);
    }
    const seedList = seeds.subarray(0, nSeeds);
    let ring = null;
    if (!this.flat) ring = this.updateNormalsAround(seedList);
    if (damage) {
      if (this.screen.length < 2 * f.nv) {
        const s = new Float32Array(2 * Math.ceil(1.25 * f.nv));
        s.set(this.screen);
        this.screen = s;
      }
      if (!this.projectSome(p.vIdx)) damage = null;
      else {
        if (!ring) ring = this.touchedVertices(seedList, true);
        damage = this.ringBounds(ring.list, ring.n, damage);
      }
    }
    this.screenFor = damage ? f.positions : null;
    this.updateMask();
    this.requestRender(damage);
    return false;
  }

  /** Screen bounds, before a sparse frame moves them, of the moved vertices
   * (projecting the whole mesh first when the view changed). Null: unknown. */
  oldDamage(idx) {
    const f = this.frame;
    this.camera.updateMatrixWorld();
    if (!this.screen || this.screenFor !== f.positions || this.screenSig !== this.viewSig()) {
      if (!this.projectAll()) return null;
    }
    return this.screenBounds(idx, idx.length);
  }

  /** Vertices whose vanish-mask bit differs from the mask on screen
   * (`keepMask`); null when unknown. */
  maskChanges(mask) {
    const old = this.maskShown, nv = this.frame.nv;
    if (!mask && !old) return { list: null, n: 0 };
    if ((mask && mask.length !== nv) || (old && old.length !== nv)) return null;
    if (!this.maskDiff || this.maskDiff.length !== nv) this.maskDiff = new Uint32Array(nv);
    const out = this.maskDiff;
    let n = 0;
    for (let v = 0; v < nv; v++) {
      if ((mask ? mask[v] : 0) !== (old ? old[v] : 0)) out[n++] = v;
    }
    return { list: out, n };
  }

  /** Remember the vanish mask now shown (frames' arrays are not ours to keep). */
  keepMask(mask) {
    if (!mask) {
      this.maskShown = null;
      return;
    }
    if (!this.maskBuf || this.maskBuf.length !== mask.length) this.maskBuf = new Uint8Array(mask.length);
    this.maskBuf.set(mask);
    this.maskShown = this.maskBuf;
  }

  disposeMesh() {
    this.disposePartMesh();
    for (const m of [this.mesh, this.wire, this.selMesh, this.maskMesh]) {
      if (!m) continue;
      this.scene.remove(m);
      m.geometry.dispose();
    }
    this.mesh = this.wire = this.selMesh = this.maskMesh = null;
  }

  computeBounds() {
    const p = this.frame.positions;
    let x0 = Infinity, y0 = Infinity, z0 = Infinity, x1 = -Infinity, y1 = -Infinity, z1 = -Infinity;
    for (let i = 0; i < p.length; i += 3) {
      const x = p[i], y = p[i + 1], z = p[i + 2];
      if (x < x0) x0 = x; if (x > x1) x1 = x;
      if (y < y0) y0 = y; if (y > y1) y1 = y;
      if (z < z0) z0 = z; if (z > z1) z1 = z;
    }
    if (!(x0 <= x1)) x0 = y0 = z0 = x1 = y1 = z1 = 0;
    const diag = Math.hypot(x1 - x0, y1 - y0, z1 - z0) || 1;
    this.bbox = { min: [x0, y0, z0], max: [x1, y1, z1], center: [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2], diag };
  }

  /** Area-weighted vertex normals straight on the typed arrays (three's
   * computeVertexNormals goes through Vector3 objects and is far slower). */
  updateNormals() {
    const f = this.frame;
    const attr = this.mesh.geometry.attributes.normal;
    areaNormals(f.positions, f.tris, attr.array);
    markWhole(attr);
  }

  /** Collect distinct vertices into the scratch list: the given ones, and
   * with `ring` every vertex of a triangle around them. Sorted. */
  touchedVertices(idx, ring) {
    const f = this.frame, nv = f.nv;
    if (!this.stamp || this.stamp.length < nv) {
      this.stamp = new Uint32Array(Math.ceil(1.25 * nv));
      this.touched = new Uint32Array(this.stamp.length);
      this.epoch = 0;
    }
    if (++this.epoch === 0xffffffff) {
      this.stamp.fill(0);
      this.epoch = 1;
    }
    const stamp = this.stamp, out = this.touched, e = this.epoch;
    let n = 0;
    if (!ring) {
      for (let i = 0; i < idx.length; i++) {
        const v = idx[i];
        if (stamp[v] !== e) { stamp[v] = e; out[n++] = v; }
      }
    } else {
      if (!this.adj) this.adj = vertexTriangles(nv, f.tris);
      const { start, tri } = this.adj, t = f.tris;
      for (let i = 0; i < idx.length; i++) {
        const v = idx[i];
        for (let j = start[v], end = start[v + 1]; j < end; j++) {
          const o = 3 * tri[j];
          for (let c = 0; c < 3; c++) {
            const w = t[o + c];
            if (stamp[w] !== e) { stamp[w] = e; out[n++] = w; }
          }
        }
      }
    }
    const list = out.subarray(0, n);
    list.sort();
    return { list, n };
  }

  /** Normals of the vertices whose triangles touch a moved vertex (the moved
   * ones and their ring), from the CSR adjacency: same area weighting as
   * updateNormals, at a cost proportional to the stroke, not the mesh. */
  updateNormalsAround(moved) {
    const f = this.frame, attr = this.mesh.geometry.attributes.normal;
    if (moved.length > f.nv / 4) {
      this.updateNormals();
      return null;
    }
    const { list, n: count } = this.touchedVertices(moved, true);
    const { start, tri } = this.adj, t = f.tris, p = f.positions, n = attr.array;
    for (let i = 0; i < count; i++) {
      const v = list[i];
      let sx = 0, sy = 0, sz = 0;
      for (let j = start[v], end = start[v + 1]; j < end; j++) {
        const o = 3 * tri[j];
        const a = 3 * t[o], b = 3 * t[o + 1], c = 3 * t[o + 2];
        const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
        const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
        sx += uy * vz - uz * vy; sy += uz * vx - ux * vz; sz += ux * vy - uy * vx;
      }
      const l = Math.hypot(sx, sy, sz) || 1;
      n[3 * v] = sx / l; n[3 * v + 1] = sy / l; n[3 * v + 2] = sz / l;
    }
    markRanges(attr, list, count, 3);
    return { list, n: count };
  }

  setFlat(flat) {
    this.flat = flat;
    this.material.flatShading = flat;
    this.material.needsUpdate = true;
    if (!flat && this.mesh) this.updateNormals();
    this.requestRender();
  }

  setWireframe(on) {
    this.showWire = on;
    if (this.wire) this.wire.visible = on && !this.proxyShown;
    this.requestRender();
  }

  /** Triangles touching a vanishing vertex are drawn red and see-through. */
  updateMask() {
    const f = this.frame, m = this.maskMesh;
    if (!m) return;
    if (!f.mask) {
      m.visible = false;
      return;
    }
    const idx = m.geometry.index, out = idx.array, t = f.tris, mask = f.mask;
    let k = 0;
    for (let i = 0; i < t.length; i += 3) {
      const a = t[i], b = t[i + 1], c = t[i + 2];
      if (mask[a] | mask[b] | mask[c]) {
        out[k++] = a; out[k++] = b; out[k++] = c;
      }
    }
    m.geometry.setDrawRange(0, k);
    idx.needsUpdate = true;
    m.visible = k > 0;
  }

  // ---- the sculpt mask ------------------------------------------------------

  /** Show the sculpt mask of a whole frame (null: nothing masked). The
   * frame's array is not ours to keep: it is copied. */
  setSculptMask(mask) {
    const nv = this.frame?.nv ?? 0;
    this.sculptMask = mask && mask.length === nv ? Uint8Array.from(mask) : null;
    this.updateSculptMask();
  }

  /** Mask (or with `erase` unmask) the vertices within `radius` of
   * `point`, here only: the mask brush's preview until the server's frame
   * comes. Returns how many vertices changed. */
  paintMask(point, radius, erase) {
    const f = this.frame;
    if (!f) return 0;
    if (!this.sculptMask) this.sculptMask = new Uint8Array(f.nv);
    const p = f.positions, m = this.sculptMask, r2 = radius * radius, want = erase ? 0 : 1;
    let changed = 0;
    for (let v = 0; v < f.nv; v++) {
      const dx = p[3 * v] - point[0], dy = p[3 * v + 1] - point[1], dz = p[3 * v + 2] - point[2];
      if (dx * dx + dy * dy + dz * dz <= r2 && m[v] !== want) {
        m[v] = want;
        changed++;
      }
    }
    if (changed) this.updateSculptMask();
    return changed;
  }

  get maskedCount() {
    const m = this.sculptMask;
    let n = 0;
    if (m) for (let i = 0; i < m.length; i++) n += m[i];
    return n;
  }

  /** The mask into the mesh's 'masked' attribute: the material darkens
   * masked vertices' shading, interpolated across triangles. */
  updateSculptMask() {
    const attr = this.mesh?.geometry.attributes.masked;
    if (!attr) return;
    const m = this.sculptMask, out = attr.array;
    out.fill(0);
    if (m && m.length <= out.length) for (let v = 0; v < m.length; v++) out[v] = m[v];
    markWhole(attr);
    // The orbit proxy carries the mask too: built again when next needed.
    if (this.proxy && !this.proxyShown) this.disposeProxy();
    this.requestRender();
  }

  // ---- materials ------------------------------------------------------------

  /** 'studio' (lit) or a matcap's name (MATCAPS). */
  setMaterial(name) {
    if (name === this.materialName) return;
    const old = this.material;
    this.material = makeMaterial(name, this.flat);
    this.materialName = name;
    for (const m of [this.mesh, this.proxy, this.partMesh]) if (m) m.material = this.material;
    old.dispose();
    this.damage = 'full';
    this.requestRender();
  }

  /** The picture as a PNG data URL, drawn whole at rest resolution without
   * the brush ring. */
  screenshot() {
    const ring = this.brush.visible;
    this.brush.visible = false;
    this.damage = 'full';
    this.renderNow();
    const url = this.canvas.toDataURL('image/png');
    this.brush.visible = ring;
    this.requestRender();
    return url;
  }

  // ---- selection overlays -----------------------------------------------

  setSelection({ faces = [], corners = [], edges = [], edge = null } = {}) {
    const f = this.frame;
    if (!f || !this.selMesh) return;
    const want = new Set(faces);
    let idx = [];
    if (want.size) {
      const t = f.tris, tf = f.triFace;
      for (let i = 0; i < tf.length; i++) if (want.has(tf[i])) idx.push(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    }
    this.selMesh.geometry.setIndex(idx.length ? new THREE.BufferAttribute(new Uint32Array(idx), 1) : null);
    this.selMesh.visible = idx.length > 0;

    const cp = new Float32Array(3 * corners.length);
    corners.forEach(([, v], i) => cp.set(f.positions.subarray(3 * v, 3 * v + 3), 3 * i));
    this.cornerPoints.geometry.dispose();
    this.cornerPoints.geometry = new THREE.BufferGeometry();
    this.cornerPoints.geometry.setAttribute('position', new THREE.BufferAttribute(cp, 3));

    // Selected edges (a loop or ring has many) as line segments.
    const list = edge != null ? [...edges, edge] : edges;
    const shown = list.filter((i) => i >= 0 && i < f.ne);
    const ep = new Float32Array(6 * shown.length);
    shown.forEach((i, k) => {
      const a = f.edges[2 * i], b = f.edges[2 * i + 1];
      ep.set(f.positions.subarray(3 * a, 3 * a + 3), 6 * k);
      ep.set(f.positions.subarray(3 * b, 3 * b + 3), 6 * k + 3);
    });
    this.edgeLine.geometry.dispose();
    this.edgeLine.geometry = new THREE.BufferGeometry();
    this.edgeLine.geometry.setAttribute('position', new THREE.BufferAttribute(ep, 3));
    this.requestRender();
  }

  // ---- brush cursor -------------------------------------------------------

  showBrush(point, normal, radius) {
    const b = this.brush;
    const before = this.brushBounds();
    b.position.set(point[0], point[1], point[2]);
    this._v.set(normal[0], normal[1], normal[2]);
    b.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), this._v.normalize());
    b.scale.setScalar(radius);
    b.visible = true;
    this._brushRadius = radius;
    const after = this.brushBounds();
    this.requestRender(before && after ? unionRect(before, after) : undefined);
  }

  hideBrush() {
    if (!this.brush.visible) return;
    const before = this.brushBounds();
    this.brush.visible = false;
    this.requestRender(before ?? undefined);
  }

  // ---- camera ---------------------------------------------------------------

  get ortho() {
    return this.camera === this.orthoCamera;
  }

  /** The projection of the current camera for the canvas's aspect. */
  updateProjection() {
    const a = this.aspect || 1;
    this.perspCamera.aspect = a;
    this.perspCamera.updateProjectionMatrix();
    const o = this.orthoCamera, h = this.orthoHalf;
    o.left = -h * a; o.right = h * a; o.top = h; o.bottom = -h;
    o.updateProjectionMatrix();
  }

  /** Orthographic (true) or perspective projection, keeping what is seen:
   * the same view direction and, at the orbit target, the same size. */
  setOrtho(on) {
    if (on === this.ortho) return;
    const from = this.camera, to = on ? this.orthoCamera : this.perspCamera;
    const target = this.controls ? this.controls.target.clone() : new THREE.Vector3(...this.bbox.center);
    const offset = from.position.clone().sub(target);
    const dist = offset.length() || 1;
    const tan = Math.tan(THREE.MathUtils.degToRad(this.perspCamera.fov / 2));
    if (on) {
      this.orthoHalf = dist * tan;
      to.zoom = 1;
      to.position.copy(from.position);
    } else {
      const half = this.orthoHalf / (from.zoom || 1);
      to.position.copy(target).addScaledVector(offset.normalize(), half / tan);
    }
    to.quaternion.copy(from.quaternion);
    to.up.copy(from.up);
    to.near = from.near;
    to.far = from.far;
    to.add(this.key);
    this.camera = to;
    this.updateProjection();
    if (this.controls) {
      this.controls.object = to;
      this.quietChange = true;
      this.controls.update();
      this.quietChange = false;
    }
    this.damage = 'full';
    this.requestRender();
  }

  /** Frame the mesh. `dir` is the direction from the target to the camera. */
  setView(dir = [0.35, 0.35, 1]) {
    const { center, diag } = this.bbox;
    const cam = this.camera;
    const r = diag / 2;
    const fov = this.perspCamera.fov;
    const dist = r / Math.sin(THREE.MathUtils.degToRad(fov / 2)) * 1.05;
    const d = new THREE.Vector3(...dir).normalize();
    cam.position.set(center[0] + d.x * dist, center[1] + d.y * dist, center[2] + d.z * dist);
    cam.up.set(0, 1, 0);
    cam.near = diag / 500;
    cam.far = diag * 100;
    if (this.ortho) {
      this.orthoHalf = r * 1.05;
      cam.zoom = 1;
    }
    this.updateProjection();
    if (this.controls) {
      this.controls.target.set(...center);
      this.quietChange = true; // a jump, not a motion
      this.controls.update();
      this.quietChange = false;
    } else {
      cam.lookAt(...center);
    }
    this.requestRender();
  }

  // ---- picking --------------------------------------------------------------

  /** World-space ray through a client (CSS pixel) position. */
  rayAt(clientX, clientY) {
    const r = this.canvas.getBoundingClientRect();
    this._v2.set(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
    this.camera.updateMatrixWorld();
    this._ray.setFromCamera(this._v2, this.camera);
    const { origin, direction } = this._ray.ray;
    return { o: [origin.x, origin.y, origin.z], d: [direction.x, direction.y, direction.z] };
  }

  /** Nearest triangle hit (both sides), brute force over the typed arrays:
   * Möller–Trumbore with no allocation per triangle, ~10 ms per million. */
  pick(clientX, clientY) {
    const f = this.frame;
    if (!f || !f.nt) return null;
    const { o, d } = this.rayAt(clientX, clientY);
    const p = f.positions, t = f.tris;
    const [ox, oy, oz] = o, [dx, dy, dz] = d;
    let best = Infinity, bestTri = -1;
    for (let i = 0, n = t.length; i < n; i += 3) {
      const a = 3 * t[i], b = 3 * t[i + 1], c = 3 * t[i + 2];
      const ax = p[a], ay = p[a + 1], az = p[a + 2];
      const e1x = p[b] - ax, e1y = p[b + 1] - ay, e1z = p[b + 2] - az;
      const e2x = p[c] - ax, e2y = p[c + 1] - ay, e2z = p[c + 2] - az;
      const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
      const det = e1x * px + e1y * py + e1z * pz;
      if (det > -1e-12 && det < 1e-12) continue;
      const inv = 1 / det;
      const sx = ox - ax, sy = oy - ay, sz = oz - az;
      const u = (sx * px + sy * py + sz * pz) * inv;
      if (u < 0 || u > 1) continue;
      const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
      const v = (dx * qx + dy * qy + dz * qz) * inv;
      if (v < 0 || u + v > 1) continue;
      const dist = (e2x * qx + e2y * qy + e2z * qz) * inv;
      if (dist > 0 && dist < best) {
        best = dist;
        bestTri = i / 3;
      }
    }
    if (bestTri < 0) return null;
    const point = [ox + dx * best, oy + dy * best, oz + dz * best];
    const a = 3 * t[3 * bestTri], b = 3 * t[3 * bestTri + 1], c = 3 * t[3 * bestTri + 2];
    const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
    const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
    let normal = [uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx];
    // Face the viewer, so the brush ring sits on the side being looked at.
    if (normal[0] * dx + normal[1] * dy + normal[2] * dz > 0) normal = normal.map((x) => -x);
    return { point, tri: bestTri, face: f.triFace[bestTri], normal, dist: best, ray: { o, d } };
  }

  /** The distinct vertices of one polygon (from its display triangles). */
  faceVertices(face) {
    const f = this.frame, out = new Set();
    for (let i = 0; i < f.triFace.length; i++) {
      if (f.triFace[i] === face) out.add(f.tris[3 * i]).add(f.tris[3 * i + 1]).add(f.tris[3 * i + 2]);
    }
    return [...out];
  }

  nearestVertex(verts, q) {
    const p = this.frame.positions;
    let best = -1, bd = Infinity;
    for (const v of verts) {
      const d = (p[3 * v] - q[0]) ** 2 + (p[3 * v + 1] - q[1]) ** 2 + (p[3 * v + 2] - q[2]) ** 2;
      if (d < bd) { bd = d; best = v; }
    }
    return best;
  }

  /** Index of the polygon edge of `face` nearest to point q. */
  nearestEdge(face, q) {
    const f = this.frame, p = f.positions, e = f.edges;
    const verts = new Set(this.faceVertices(face));
    let best = -1, bd = Infinity;
    for (let i = 0; i < f.ne; i++) {
      const a = e[2 * i], b = e[2 * i + 1];
      if (!verts.has(a) || !verts.has(b)) continue;
      const ax = p[3 * a], ay = p[3 * a + 1], az = p[3 * a + 2];
      const bx = p[3 * b] - ax, by = p[3 * b + 1] - ay, bz = p[3 * b + 2] - az;
      const qx = q[0] - ax, qy = q[1] - ay, qz = q[2] - az;
      const l2 = bx * bx + by * by + bz * bz || 1;
      const s = Math.max(0, Math.min(1, (qx * bx + qy * by + qz * bz) / l2));
      const d = (qx - s * bx) ** 2 + (qy - s * by) ** 2 + (qz - s * bz) ** 2;
      if (d < bd) { bd = d; best = i; }
    }
    return best;
  }

  /** Client (CSS pixel) position of a world point. */
  project(point) {
    const r = this.canvas.getBoundingClientRect();
    // The camera may have moved since the last picture (a view key).
    this.camera.updateMatrixWorld();
    this._v.set(point[0], point[1], point[2]).project(this.camera);
    return [r.left + ((this._v.x + 1) / 2) * r.width, r.top + ((1 - this._v.y) / 2) * r.height];
  }

  /** Client pixels per model unit across the screen at a world point. */
  pixelsPerUnit(point) {
    this.camera.updateMatrixWorld();
    const right = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 0).normalize();
    const e = this.bbox.diag * 1e-3 || 1e-3;
    const a = this.project(point);
    const b = this.project([point[0] + right.x * e, point[1] + right.y * e, point[2] + right.z * e]);
    return Math.hypot(b[0] - a[0], b[1] - a[1]) / e || 1;
  }

  /** The unit vector from the view towards the camera (a ring facing the viewer). */
  towardsCamera() {
    const d = this.camera.getWorldDirection(new THREE.Vector3());
    return [-d.x, -d.y, -d.z];
  }

  /** Point where the ray through a client position meets the plane through
   * `anchor` facing the camera (grab/move drags into empty space). */
  planePoint(clientX, clientY, anchor) {
    const { o, d } = this.rayAt(clientX, clientY);
    const n = this.camera.getWorldDirection(this._v);
    const denom = n.x * d[0] + n.y * d[1] + n.z * d[2];
    if (Math.abs(denom) < 1e-9) return null;
    const s = (n.x * (anchor[0] - o[0]) + n.y * (anchor[1] - o[1]) + n.z * (anchor[2] - o[2])) / denom;
    return [o[0] + d[0] * s, o[1] + d[1] * s, o[2] + d[2] * s];
  }
}

/** Smallest rectangle holding both (either may be empty: x0 > x1). */
function unionRect(a, b) {
  if (!a) return b;
  return { x0: Math.min(a.x0, b.x0), y0: Math.min(a.y0, b.y0), x1: Math.max(a.x1, b.x1), y1: Math.max(a.y1, b.y1) };
}

/** Mark the parts of an attribute holding the given sorted items for upload:
 * a few ranges when they cluster, the whole buffer otherwise. Ranges of
 * several frames add up until the next render uploads them. */
function markRanges(attr, sorted, n, itemSize) {
  if (!n || attr.wholePending) return;
  const runs = n > attr.count / 4 ? null : indexRuns(sorted, n);
  if (!runs || attr.updateRanges.length + runs.length / 2 > 96) {
    markWhole(attr);
    return;
  }
  for (let i = 0; i < runs.length; i += 2) attr.addUpdateRange(runs[i] * itemSize, runs[i + 1] * itemSize);
  attr.needsUpdate = true;
}

/** Upload the whole attribute at the next render (whatever ranges came before). */
function markWhole(attr) {
  attr.clearUpdateRanges();
  attr.wholePending = true;
  attr.needsUpdate = true;
}

/** A BufferAttribute whose `wholePending` says a full upload is due. */
function liveAttribute(array, itemSize) {
  const a = new THREE.BufferAttribute(array, itemSize);
  a.wholePending = false;
  a.onUpload(() => { a.wholePending = false; });
  return a;
}

const onIdle = (fn) => (window.requestIdleCallback ? requestIdleCallback(fn, { timeout: 1500 }) : setTimeout(fn, 300));
const cancelIdle = (id) => (window.cancelIdleCallback ? cancelIdleCallback(id) : clearTimeout(id));


// ---- materials ----------------------------------------------------------------

/** The matcaps offered, each drawn here into a canvas: a sphere's picture
 * under a fixed light, looked up by each fragment's view-space normal. */
export const MATCAPS = {
  clay: { base: [0.78, 0.55, 0.42], ambient: 0.28, light: [-0.45, 0.6, 0.66], spec: 0.12, shine: 12, rim: 0.15 },
  pearl: { base: [0.9, 0.9, 0.93], ambient: 0.35, light: [-0.3, 0.5, 0.81], spec: 0.55, shine: 40, rim: 0.35, rimColor: [0.75, 0.8, 1] },
  jade: { base: [0.3, 0.62, 0.45], ambient: 0.3, light: [0.4, 0.6, 0.69], spec: 0.4, shine: 60, rim: 0.45, rimColor: [0.65, 1, 0.8] },
  'red-wax': { base: [0.72, 0.12, 0.1], ambient: 0.25, light: [-0.5, 0.55, 0.67], spec: 0.5, shine: 25, rim: 0.2, rimColor: [1, 0.5, 0.4] },
  chrome: { env: true },
};

const matcapTextures = new Map();

/** A matcap texture, made once: for every pixel inside the disc, the
 * normal n = (x, y, √(1 − x² − y²)) shaded by an ambient term, Lambert,
 * Blinn–Phong and a rim; chrome reflects a sky-over-ground horizon. */
function matcapTexture(name) {
  if (matcapTextures.has(name)) return matcapTextures.get(name);
  const m = MATCAPS[name];
  const size = 256;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(size, size);
  const L = m.light ? normalize3(m.light) : null;
  const H = L ? normalize3([L[0], L[1], L[2] + 1]) : null;
  for (let j = 0; j < size; j++) {
    for (let i = 0; i < size; i++) {
      const x = ((i + 0.5) / size) * 2 - 1, y = 1 - ((j + 0.5) / size) * 2;
      const rr = Math.min(1, x * x + y * y), z = Math.sqrt(1 - rr);
      let c;
      if (m.env) {
        // Reflect the view ray (0, 0, −1) about n; sky above, ground below.
        const ry = 2 * z * y, rz = 2 * z * z - 1;
        const t = ry;
        const sky = [0.55 + 0.4 * t, 0.62 + 0.35 * t, 0.75 + 0.25 * t];
        const ground = [0.22 - 0.1 * t, 0.18 - 0.08 * t, 0.15 - 0.05 * t];
        c = t > 0 ? sky : ground;
        const glint = Math.pow(Math.max(0, 1 - Math.abs(t - 0.02) * 12), 2) * 0.6;
        const back = Math.max(0, -rz) * 0.15;
        c = c.map((v) => v + glint + back);
      } else {
        const diff = Math.max(0, x * L[0] + y * L[1] + z * L[2]);
        const spec = m.spec * Math.pow(Math.max(0, x * H[0] + y * H[1] + z * H[2]), m.shine);
        const rim = m.rim * Math.pow(1 - z, 3);
        const rc = m.rimColor || [1, 1, 1];
        c = m.base.map((b, k) => b * (m.ambient + (1 - m.ambient) * diff) + spec + rim * rc[k]);
      }
      const o = 4 * (j * size + i);
      for (let k = 0; k < 3; k++) img.data[o + k] = Math.round(255 * Math.min(1, Math.max(0, c[k])));
      img.data[o + 3] = 255;
    }
  }
  ctx.putImageData(img, 0, 0);
  const tex = new THREE.CanvasTexture(canvas);
  tex.colorSpace = THREE.SRGBColorSpace;
  matcapTextures.set(name, tex);
  return tex;
}

function normalize3(v) {
  const l = Math.hypot(v[0], v[1], v[2]) || 1;
  return [v[0] / l, v[1] / l, v[2] / l];
}

/** The surface material: the lit studio (Phong) or a matcap. Both push
 * the surface back so the wireframe and overlays draw on top of it. */
function makeMaterial(name, flat) {
  const common = {
    side: THREE.DoubleSide, flatShading: flat,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  };
  const m = name in MATCAPS
    ? new THREE.MeshMatcapMaterial({ matcap: matcapTexture(name), ...common })
    : new THREE.MeshPhongMaterial({ color: BASE_COLOR, specular: 0x222222, shininess: 30, ...common });
  return withSculptMask(m);
}

/** What masked vertices' light is multiplied by (linear RGB, before
 * tone mapping and sRGB encoding): a dark slate, so the masked part reads
 * at once yet keeps the material's shading, highlights and rim, and so
 * its shape (a flat overlay hides the form under it). */
const MASK_TINT = [0.2, 0.23, 0.3];

/** The material with the sculpt mask: a per-vertex `masked` attribute
 * (0 or 1, interpolated over triangles; the orbit proxy's clusters carry
 * the share of their vertices masked) multiplies the shaded colour by
 * MASK_TINT. A mesh without the attribute reads 0. */
function withSculptMask(material) {
  material.onBeforeCompile = (shader) => {
    shader.vertexShader = 'attribute float masked;\nvarying float vMasked;\n' +
      shader.vertexShader.replace('#include <begin_vertex>', '#include <begin_vertex>\n\tvMasked = masked;');
    const tint = MASK_TINT.map((c) => c.toFixed(3)).join(', ');
    shader.fragmentShader = 'varying float vMasked;\n' +
      shader.fragmentShader.replace('#include <opaque_fragment>',
        `outgoingLight *= mix(vec3(1.0), vec3(${tint}), vMasked);\n\t#include <opaque_fragment>`);
  };
  material.customProgramCacheKey = () => 'sculpt-mask';
  return material;
}
