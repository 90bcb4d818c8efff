// The robot in 3D from the URDF the servers run, its joints moved by joint_states; the camera frames the whole
// robot when it loads and at the fit button. Without WebGL the view says so and the URDF still gives the joints.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import URDFLoader from 'urdf-loader';
import { el, kTitleChars, shown } from './dom.js';
import { fitDistance, screenRect } from './fit.js';
import { loadMesh } from './meshes.js';

export class RobotView {
  constructor(container, note, fitButton) {
    this.el = container;
    this.note = note;
    this.robot = null;
    this.joints = {}; // name -> {type, lower, upper, velocity, effort}
    this.onLoad = [];
    this.moved = false; // the user turned or zoomed the view since it was last fitted
    try {
      this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      fitButton.hidden = true;
      container.appendChild(el('div', { class: 'view-message' },
        `No 3D view: this browser gives the page no WebGL (${e.message || e}).`,
        ' Turn on WebGL or hardware acceleration in its settings, or open the page in another browser;',
        ' the rest of the dashboard works without it.'));
      return;
    }
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f5f7);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 100);
    this.camera.position.set(1.6, 1.2, 1.6);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.0));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(3, 5, 2);
    this.scene.add(sun);
    const grid = new THREE.GridHelper(4, 40, 0x999999, 0xcccccc);
    this.scene.add(grid);
    this.scene.add(new THREE.AxesHelper(0.3));
    container.appendChild(this.renderer.domElement);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0.4, 0);
    this.controls.addEventListener('change', () => this.invalidate());
    this.controls.addEventListener('start', () => { this.moved = true; });
    fitButton.onclick = () => this.fit();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  // The robot's bounding box in the scene: its links' origins (a robot with no visual still has those) and shapes,
  // but not the shapes of a link welded to the root (a ground plane, a table, a world of its own) that would
  // dwarf the links that move: a 5 x 5 m plane under an arm would leave the arm a speck.
  box() {
    this.world.updateMatrixWorld(true);
    const links = Object.values(this.robot.links || {});
    const box = new THREE.Box3();
    for (const link of links) box.expandByPoint(link.getWorldPosition(new THREE.Vector3()));
    const shapes = (link) => {
      const b = new THREE.Box3();
      for (const c of link.children) if (!c.isURDFJoint && !c.isURDFLink) b.expandByObject(c);
      return b;
    };
    const moving = new THREE.Box3();
    for (const link of links) if (this.moves(link)) moving.union(shapes(link));
    box.union(moving);
    const reach = moving.isEmpty() ? Infinity : 2 * moving.getSize(new THREE.Vector3()).length();
    this.leftOut = [];
    for (const link of links) {
      if (this.moves(link)) continue;
      const b = shapes(link);
      if (b.isEmpty()) continue;
      if (b.getSize(new THREE.Vector3()).length() <= reach) box.union(b);
      else this.leftOut.push(link);
    }
    return box;
  }

  // Whether a link moves: a joint that is not fixed lies between it and the root.
  moves(link) {
    for (let o = link.parent; o && o !== this.world; o = o.parent) if (o.isURDFJoint && o.jointType !== 'fixed') return true;
    return false;
  }

  // Points on the robot's surface in the world: at most ~kPointsPerMesh vertices of each shape the box takes in, and
  // the links' origins. What the camera frames, tighter than the box's corners, which stand off a bent arm.
  surfacePoints() {
    const kPointsPerMesh = 400;
    this.box(); // decides this.leftOut
    const out = [];
    const left = new Set(this.leftOut);
    const v = new THREE.Vector3();
    for (const link of Object.values(this.robot.links || {})) {
      out.push(link.getWorldPosition(new THREE.Vector3()));
      if (left.has(link)) continue;
      for (const c of link.children) {
        if (c.isURDFJoint || c.isURDFLink) continue;
        c.traverse((o) => {
          const pos = o.isMesh && o.geometry?.attributes?.position;
          if (!pos) return;
          const stride = Math.max(1, Math.floor(pos.count / kPointsPerMesh));
          for (let i = 0; i < pos.count; i += stride) out.push(v.fromBufferAttribute(pos, i).applyMatrix4(o.matrixWorld).clone());
        });
      }
    }
    return out;
  }

  // The camera looks at the robot from where it looks now: first far enough to see its bounding sphere, then, a few
  // times over, turned onto the middle of the robot's silhouette and moved until the silhouette fills 90 % of the
  // view's width or height, whichever it reaches first (a sphere, or the box's corners, around a tall thin arm leave
  // most of the view empty).
  fit() {
    if (!this.renderer || !this.world) return;
    const sphere = this.box().getBoundingSphere(new THREE.Sphere());
    const radius = Math.max(sphere.radius, 0.05);
    const direction = this.camera.position.clone().sub(this.controls.target);
    if (direction.lengthSq() < 1e-12) direction.set(1, 0.5, 1);
    direction.normalize();
    let distance = fitDistance(radius, this.camera.fov, this.camera.aspect);
    this.controls.target.copy(sphere.center);
    const place = () => {
      this.camera.position.copy(this.controls.target).addScaledVector(direction, distance);
      this.camera.near = distance / 100;
      this.camera.far = distance * 100;
      this.camera.updateProjectionMatrix();
      this.camera.updateMatrixWorld();
    };
    place();
    const points = this.surfacePoints();
    const silhouette = () => this.projectedRobot(points);
    let whole = null; // the last framing that showed all of it
    for (let k = 0; k < 12; ++k) {
      const r = silhouette();
      const fill = Math.max((r.right - r.left) / r.width, (r.bottom - r.top) / r.height);
      if (!r.inside) {
        if (!whole) break;
        // Too close (a near corner grows faster than the rest): halfway back to the last framing that showed all.
        distance = (distance + whole.distance) / 2;
        this.controls.target.lerp(whole.target, 0.5);
        place();
        continue;
      }
      if (!(fill > 0.02)) break;
      whole = { distance, target: this.controls.target.clone() };
      // The silhouette's middle, from the centre in NDC, moved to the centre at the target's depth.
      const mx = (r.left + r.right) / r.width - 1, my = 1 - (r.top + r.bottom) / r.height;
      const halfH = Math.tan((this.camera.fov * Math.PI) / 360) * distance, halfW = halfH * this.camera.aspect;
      const right = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 0);
      const up = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 1);
      const centred = Math.abs(mx) < 0.02 && Math.abs(my) < 0.02;
      if (centred && fill > 0.86 && fill < 0.92) break;
      this.controls.target.addScaledVector(right, mx * halfW).addScaledVector(up, my * halfH);
      distance *= fill / 0.9;
      place();
    }
    if (whole && !silhouette().inside) {
      distance = whole.distance;
      this.controls.target.copy(whole.target);
      place();
    }
    this.controls.update();
    this.moved = false;
    this.invalidate();
  }

  // Where the robot's surface (surfacePoints) falls on the canvas, in CSS pixels ({left, top, right, bottom, width,
  // height, inside}): what fit() frames; null without a robot or WebGL. For the browser test, and for anyone asking
  // from the console.
  projectedRobot(points = null) {
    if (!this.renderer || !this.world) return null;
    const canvas = this.renderer.domElement;
    return screenRect((points || this.surfacePoints()).map((p) => p.clone().project(this.camera)), canvas.clientWidth,
      canvas.clientHeight);
  }

  // Where the robot's bounding box falls on the canvas, in CSS pixels ({left, top, right, bottom, width, height,
  // inside}); null without a robot or WebGL. For the browser test, and for anyone asking from the console.
  projectedBox() {
    if (!this.renderer || !this.world) return null;
    const b = this.box();
    const corners = [];
    for (const x of [b.min.x, b.max.x]) for (const y of [b.min.y, b.max.y]) for (const z of [b.min.z, b.max.z])
      corners.push(new THREE.Vector3(x, y, z).project(this.camera));
    const canvas = this.renderer.domElement;
    return screenRect(corners, canvas.clientWidth, canvas.clientHeight);
  }

  // The share of the view's pixels the robot covers, drawn once without the grid, the axes and the links the frame
  // leaves out (a ground plane), and read back from the canvas; null without a robot or WebGL. For the browser test,
  // and for anyone asking from the console.
  coverage() {
    if (!this.renderer || !this.world) return null;
    this.box();
    const helpers = this.scene.children.filter((c) => c.type === 'GridHelper' || c.type === 'AxesHelper');
    for (const link of this.leftOut) for (const c of link.children) if (!c.isURDFJoint && !c.isURDFLink) helpers.push(c);
    for (const h of helpers) h.visible = false;
    this.renderer.render(this.scene, this.camera);
    const gl = this.renderer.getContext();
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    for (const o of helpers) o.visible = true;
    this.invalidate();
    const bg = px.slice(0, 3); // a corner: the background
    let covered = 0;
    for (let i = 0; i < px.length; i += 4)
      if (Math.abs(px[i] - bg[0]) + Math.abs(px[i + 1] - bg[1]) + Math.abs(px[i + 2] - bg[2]) > 12) ++covered;
    return covered / (w * h);
  }

  // Draws on the next animation frame, once however often it is asked: a still robot costs the browser nothing.
  invalidate() {
    if (this.pending || !this.renderer) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
    });
  }

  resize() {
    if (!this.renderer) return;
    const r = this.el.getBoundingClientRect();
    const w = Math.max(100, r.width);
    const h = Math.max(100, r.height);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    if (this.world && !this.moved) this.fit(); // a narrower view needs the camera further away
    else this.invalidate();
  }

  load(url) {
    if (!url) {
      this.note.textContent = 'no URDF: start the dashboard with --urdf FILE to see the robot';
      return;
    }
    // Meshes arrive after the URDF: draw again as each one loads.
    const manager = new THREE.LoadingManager();
    manager.onProgress = () => this.invalidate();
    const failed = [];
    manager.onError = (mesh) => {
      failed.push(mesh);
      this.meshNote = `${failed.length} mesh${failed.length > 1 ? 'es' : ''} not shown (first: ${failed[0]}): meshes ` +
        "are served from packages on --package-path and the URDF's folder";
      this.note.textContent = shown(`${this.loadedNote || ''} · ${this.meshNote}`, kTitleChars);
      this.note.classList.add('error');
    };
    manager.onLoad = () => (this.moved || !this.world ? this.invalidate() : this.fit()); // meshes change the box
    const loader = new URDFLoader(manager);
    loader.packages = (pkg) => `/package/${pkg}`;
    loader.loadMeshCb = loadMesh;
    loader.load(
      url,
      (robot) => {
        if (this.world) this.scene.remove(this.world);
        this.world = new THREE.Group();
        this.world.rotation.x = -Math.PI / 2; // URDF and the base pose are z-up, three.js is y-up
        this.world.add(robot);
        this.robot = robot;
        this.posed = false;
        if (this.scene) this.scene.add(this.world);
        this.joints = {};
        for (const [name, j] of Object.entries(robot.joints)) {
          if (j.jointType === 'fixed') continue;
          this.joints[name] = {
            type: j.jointType,
            lower: Number(j.limit?.lower ?? 0),
            upper: Number(j.limit?.upper ?? 0),
            velocity: Number(j.limit?.velocity ?? 0),
            effort: Number(j.limit?.effort ?? 0),
          };
        }
        this.loadedNote = `${robot.robotName || 'robot'} from ${url}`;
        this.note.textContent = shown(this.meshNote ? `${this.loadedNote} · ${this.meshNote}` : this.loadedNote, kTitleChars);
        this.fit();

        for (const fn of this.onLoad) fn(this.joints);
      },
      undefined,
      (err) => {
        this.note.textContent = `could not load ${url}: ${err?.message || err}`;
      },
    );
  }

  // A mobile robot's base in the world (sim_server/base_pose, z-up).
  setBase(position, orientation) {
    if (!this.robot || !position || !orientation) return;
    this.robot.position.set(position.x, position.y, position.z);
    this.robot.quaternion.set(orientation.x, orientation.y, orientation.z, orientation.w);
    this.invalidate();
  }

  setJoints(names, positions) {
    if (!this.robot) return;
    let moved = false;
    names.forEach((n, k) => {
      if (this.robot.joints[n] && Number.isFinite(positions[k])) moved = this.robot.joints[n].setJointValue(positions[k]) || moved;
    });
    if (!this.posed) {
      this.posed = true; // framed again as the robot stands (a start pose far from all zeros), unless the user moved
      if (!this.moved) return this.fit();
    }
    if (moved) this.invalidate();
  }
}
