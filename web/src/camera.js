// The page's camera, from the library's numbers (docs/conventions.md, "Camera"): prt web
// writes render::meshFraming's framing (bounding sphere, view direction, up, fov, margin) or
// --camera's camera into prt-data.js, and the page only fits that sphere to its canvas as
// render::frameCamera does (tests/web/golden_check.mjs compares). The projection is
// render::RayGenerator's, with near and far planes around the bounding sphere, as prt view.

/**
 * render::frameCamera: looks at the framing's centre from `direction`, at the distance where the
 * sphere grown by `margin` fits the narrower field of view of a w × h image. framing = { centre,
 * radius, direction, up, fov, margin } (arrays of 3). Returns { eye, target, up, fov }.
 */
export function frameView(framing, w, h) {
  const halfY = (framing.fov / 2) * Math.PI / 180, halfX = Math.atan(Math.tan(halfY) * w / h);
  const d = (framing.margin * Math.max(framing.radius, 1e-6)) / Math.sin(Math.min(halfX, halfY));
  const [x, y, z] = framing.direction, n = Math.hypot(x, y, z);
  const c = framing.centre;
  return { eye: [c[0] + (x / n) * d, c[1] + (y / n) * d, c[2] + (z / n) * d], target: c.slice(),
           up: framing.up.slice(), fov: framing.fov };
}

/** Puts a view { eye, target, up, fov } on a three.js camera (and the orbit controls' target). */
export function applyView(camera, controls, view) {
  camera.fov = view.fov;
  camera.up.fromArray(view.up);
  camera.position.fromArray(view.eye);
  camera.lookAt(view.target[0], view.target[1], view.target[2]);
  if (controls) controls.target.fromArray(view.target), controls.update();
}

/** The projection for a w × h frame: near and far around the bounding sphere (as the desktop
 *  renderer: depth d of the centre, everything within d ± 1.01 r). */
export function fitProjection(camera, w, h, centre, radius) {
  camera.aspect = w / h;
  camera.updateMatrixWorld();
  const forward = camera.getWorldDirection(camera.position.clone().set(0, 0, 0));
  const d = (centre.x - camera.position.x) * forward.x + (centre.y - camera.position.y) * forward.y +
            (centre.z - camera.position.z) * forward.z;
  camera.far = Math.max(d + 1.01 * radius, 1e-3 * radius);
  camera.near = Math.max(d - 1.01 * radius, 1e-4 * camera.far);
  camera.updateProjectionMatrix();
  camera.updateMatrixWorld();
  return forward;
}
