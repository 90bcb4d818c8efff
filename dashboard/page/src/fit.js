// Framing the robot in the 3D view, as numbers only (no three.js, so that node tests it): how far the camera stands
// to see a bounding sphere whole, and where a set of projected points falls on the canvas.

// The distance from a sphere's centre at which a perspective camera of vertical field of view `vfovDeg` and aspect
// `aspect` (width / height) sees the whole sphere, with `margin` around it: the narrower of the two fields decides.
export function fitDistance(radius, vfovDeg, aspect, margin = 1.15) {
  const half = (vfovDeg * Math.PI) / 360;
  const halfWide = Math.atan(Math.tan(half) * aspect);
  return (margin * radius) / Math.sin(Math.min(half, halfWide));
}

// The pixel rectangle that points in normalized device coordinates (x, y in [-1, 1], y up; z in [-1, 1] in front
// of the camera) cover on a canvas of width x height, and whether all of it is on the canvas.
export function screenRect(ndc, width, height) {
  const xs = ndc.map((p) => ((p.x + 1) / 2) * width);
  const ys = ndc.map((p) => ((1 - p.y) / 2) * height);
  const rect = { left: Math.min(...xs), top: Math.min(...ys), right: Math.max(...xs), bottom: Math.max(...ys), width, height };
  rect.inside = ndc.length > 0 && ndc.every((p) => p.z >= -1 && p.z <= 1) && rect.left >= 0 && rect.top >= 0 &&
    rect.right <= width && rect.bottom <= height;
  return rect;
}
