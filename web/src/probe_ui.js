// The page's controls for a probe bake (docs/web.md, "Probe bakes"): the ball's x, y and z
// (sliders over the grid's box), Alt + left drag moving it in the view's plane, and whether the
// probes show as points; and what the status line says. The light turns as for any bake.
import * as THREE from 'three';
import { ballDefaults, gridBox } from './probe_scene.js';
import { pointerDrag } from './pointer_drag.js';

/** The panel's folder for the ball and the probes (destroy() it when the bake changes). */
export function probeControls(gui, page) {
  const { state } = page, grid = page.bake().grid, { lo, hi } = gridBox(grid);
  const folder = gui.addFolder('ball (probe grid)');
  const ball = { x: state.at[0], y: state.at[1], z: state.at[2] };
  const set = () => { state.at = [ball.x, ball.y, ball.z]; };
  const sliders = ['x', 'y', 'z'].map((k, a) =>
    folder.add(ball, k, lo[a], hi[a], (hi[a] - lo[a]) / 1000).onChange(set));
  folder.add(state, 'probes').name('show probes');
  folder.add({ reset: () => {
    [ball.x, ball.y, ball.z] = ballDefaults(grid).centre;
    set();
    sliders.forEach((c) => c.updateDisplay());
  } }, 'reset').name('reset ball');
  // The drag moves state.at: the sliders follow it.
  folder.sync = () => {
    [ball.x, ball.y, ball.z] = state.at;
    sliders.forEach((c) => c.updateDisplay());
  };
  return folder;
}

/**
 * Alt + left drag moves the ball in the plane facing the camera, as far as the pointer moves at
 * the ball's depth, kept inside the grid's box. `onMove` runs after each step (the panel's
 * sync). Listens on the canvas for the page's life; does nothing unless a probe bake is shown.
 */
export function ballDrag(page, canvas, camera, onMove) {
  pointerDrag(canvas, (e) => e.button === 0 && e.altKey && page.bake().probes, (dx, dy) => {
    const { state } = page, { lo, hi } = gridBox(page.bake().grid);
    const at = new THREE.Vector3().fromArray(state.at);
    const forward = camera.getWorldDirection(new THREE.Vector3());
    const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
    const up = new THREE.Vector3().crossVectors(right, forward);
    // World units per pixel at the ball's depth.
    const depth = at.clone().sub(camera.position).dot(forward);
    const k = (2 * Math.max(depth, 1e-6) * Math.tan((camera.fov / 2) * Math.PI / 180)) / canvas.clientHeight;
    at.addScaledVector(right, dx * k).addScaledVector(up, -dy * k);
    state.at = at.toArray().map((x, a) => Math.min(Math.max(x, lo[a]), hi[a]));
    onMove();
  });
}

/** The status line's lines for probe transfer t of bake b. */
export function describeProbes(b, t, state) {
  const g = b.grid, n = g.count[0] * g.count[1] * g.count[2];
  const at = state.at.map((x) => x.toFixed(3)).join(', ');
  return [`probe grid ${g.count.join(' x ')} (${n} probes), relit on the CPU${t.compressed ? ' from CPCA rows' : ''}`,
          `ball at (${at}): Alt + drag or the panel moves it`];
}
