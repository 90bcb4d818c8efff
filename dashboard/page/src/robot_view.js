// The robot in 3D from the URDF the servers run, its joints moved by joint_states.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import URDFLoader from 'urdf-loader';

export class RobotView {
  constructor(el, note) {
    this.el = el;
    this.note = note;
    this.robot = null;
    this.joints = {}; // name -> {type, lower, upper, velocity, effort}
    this.onLoad = [];
    try {
      this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      note.textContent = `no 3D view: WebGL is not available in this browser (${e.message})`;
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
    el.appendChild(this.renderer.domElement);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0.4, 0);
    this.controls.addEventListener('change', () => this.invalidate());
    new ResizeObserver(() => this.resize()).observe(el);
    this.resize();
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
    this.invalidate();
  }

  load(url) {
    if (!url) {
      this.note.textContent = 'no URDF: start the dashboard with --urdf FILE to see the robot';
      return;
    }
    // Meshes arrive after the URDF: draw again as each one loads.
    const manager = new THREE.LoadingManager();
    manager.onProgress = () => this.invalidate();
    manager.onLoad = () => this.invalidate();
    const loader = new URDFLoader(manager);
    loader.packages = (pkg) => `/package/${pkg}`;
    loader.load(
      url,
      (robot) => {
        if (this.world) this.scene.remove(this.world);
        this.world = new THREE.Group();
        this.world.rotation.x = -Math.PI / 2; // URDF and the base pose are z-up, three.js is y-up
        this.world.add(robot);
        this.robot = robot;
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
        this.note.textContent = `${robot.robotName || 'robot'} from ${url}`;
        this.invalidate();

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
    if (moved) this.invalidate();
  }
}
