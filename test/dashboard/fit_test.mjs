// The 3D view's framing (dashboard/page/src/fit.js): at fitDistance a camera sees the whole bounding box of robots of
// any shape (a 2 m arm, a flat base) on canvases of any aspect, projected here with a pinhole camera of our own; closer
// than that a tall robot is cut; screenRect says where points fall on the canvas. Run by ctest with node:
// node fit_test.mjs <path of fit.js>.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const src = readFileSync(process.argv[2], 'utf8');
const { fitDistance, screenRect } = await import(`data:text/javascript,${encodeURIComponent(src)}`);

const sub = (a, b) => a.map((x, k) => x - b[k]);
const dot = (a, b) => a.reduce((s, x, k) => s + x * b[k], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a) => a.map((x) => x / Math.hypot(...a));

// Normalized device coordinates of `p` for a camera at `eye` looking at `target` (y up), as three.js projects.
function project(p, eye, target, vfovDeg, aspect) {
  const f = unit(sub(target, eye));
  const r = unit(cross(f, [0, 1, 0]));
  const u = cross(r, f);
  const v = sub(p, eye);
  const depth = dot(v, f);
  const t = Math.tan((vfovDeg * Math.PI) / 360);
  return { x: dot(v, r) / (depth * t * aspect), y: dot(v, u) / (depth * t), z: depth > 0 ? 0 : 2 };
}

// The camera `distance` from the centre of the box [min, max] along `direction`: where its corners fall.
function view(min, max, direction, distance, vfovDeg, width, height) {
  const centre = min.map((x, k) => (x + max[k]) / 2);
  const eye = centre.map((c, k) => c + unit(direction)[k] * distance);
  const corners = [];
  for (const x of [min[0], max[0]]) for (const y of [min[1], max[1]]) for (const z of [min[2], max[2]])
    corners.push(project([x, y, z], eye, centre, vfovDeg, width / height));
  return screenRect(corners, width, height);
}

const radius = (min, max) => Math.hypot(...sub(max, min)) / 2;
const robots = {
  tall_arm: [[-0.1, 0, -0.1], [0.1, 2.1, 0.1]], // y up in the view: a 2.1 m arm
  turret_bot: [[-0.23, -0.09, -1.0], [0.23, 0.52, 0.05]],
  flat_base: [[-1.5, 0, -1], [1.5, 0.2, 1]],
};
for (const [name, [min, max]] of Object.entries(robots)) {
  for (const [width, height] of [[810, 440], [440, 810], [500, 500]]) {
    for (const direction of [[1.6, 0.8, 1.6], [0, 0, 1], [1, 3, 0.2]]) {
      const d = fitDistance(radius(min, max), 45, width / height);
      const r = view(min, max, direction, d, 45, width, height);
      assert.ok(r.inside, `${name} on ${width}x${height} from ${direction}: ${JSON.stringify(r)}`);
    }
  }
}
// Closer than the fit, the tall arm does not fit on a wide canvas: the check above can fail.
const [tmin, tmax] = robots.tall_arm;
const close = view(tmin, tmax, [1, 0, 0], 0.5 * fitDistance(radius(tmin, tmax), 45, 810 / 440), 45, 810, 440);
assert.equal(close.inside, false, JSON.stringify(close));
assert.ok(close.top < 0 && close.bottom > 440, JSON.stringify(close));
// The narrower field decides: a tall canvas needs the camera further away than a wide one.
assert.ok(fitDistance(1, 45, 0.5) > fitDistance(1, 45, 2));
assert.equal(fitDistance(1, 45, 2), fitDistance(1, 45, 1));

// screenRect: y up in NDC is y down on the canvas; a point behind the camera is never inside.
assert.deepEqual(screenRect([{ x: -1, y: 1, z: 0 }, { x: 0, y: 0, z: 0.5 }], 200, 100),
  { left: 0, top: 0, right: 100, bottom: 50, width: 200, height: 100, inside: true });
assert.equal(screenRect([{ x: 0, y: 0, z: 1.5 }], 200, 100).inside, false);
assert.equal(screenRect([{ x: 1.2, y: 0, z: 0 }], 200, 100).inside, false);
assert.equal(screenRect([], 200, 100).inside, false);
console.log('fit.js: whole robots in view on any canvas: ok');
