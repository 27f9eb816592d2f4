// The page's probe mode (docs/web.md, "Probe bakes"; docs/probes.md): a probe bake's scene (the
// mesh the file keeps) and a ball the user moves through it, every vertex lit through the relit
// grid around it — ρ E(n)/π from the trilinear blend of its eight probes (probe_lighting.js) — as
// `prt render BAKE --object builtin:sphere --at x,y,z` draws them (render::shadeThroughProbes).
// The radiance goes to the GPU per vertex (shaders/stages/radiance.vert, mesh.frag) into the
// frame's HDR target, like any bake's; the probes themselves can be shown as points, each the
// mean radiance arriving there. The grid is relit only when the light, its rotation, the
// transfer or the bands change; the ball is re-shaded when it moves.
import * as THREE from 'three';
import { defaultAlbedo } from 'prt:constants';
import radianceVert from 'prt:shaders/radiance.vert';
import meshFrag from 'prt:shaders/mesh.frag';
import { ProbeRelighter } from './probe_relighter.js';
import { probePosition } from './probe_lighting.js';
import { radianceMesh, shadeRadianceMesh } from './radiance_mesh.js';

const kY00 = 0.5 / Math.sqrt(Math.PI);  // Y_00: L'_00·Y_00 is the mean radiance arriving

/** The box the grid's cells fill (probes at their centres): { lo, hi } (arrays of three). */
export function gridBox(grid) {
  const lo = [0, 0, 0], hi = [0, 0, 0];
  for (let a = 0; a < 3; ++a) {
    lo[a] = grid.origin[a] - 0.5 * grid.spacing[a];
    hi[a] = grid.origin[a] + (grid.count[a] - 0.5) * grid.spacing[a];
  }
  return { lo, hi };
}

/** Where the ball starts and its radius, as prt render and prt view place --object
 *  (render::defaultObjectPosition, defaultObjectSize): the grid's centre, a fifth of the grid's
 *  largest side (its cells') across. */
export function ballDefaults(grid) {
  const { lo, hi } = gridBox(grid);
  const centre = lo.map((l, a) => 0.5 * (l + hi[a]));
  return { centre, radius: 0.1 * Math.max(...hi.map((h, a) => h - lo[a])) };
}

/** The page's material for a mesh drawn from its per-vertex radiance (radiance_mesh.js). */
function pageRadianceMaterial() {
  return new THREE.RawShaderMaterial({ glslVersion: THREE.GLSL3, vertexShader: radianceVert, fragmentShader: meshFrag,
                                       side: THREE.DoubleSide });
}

/** The probes as points (hidden until asked for). */
function probePoints(grid) {
  const P = grid.count[0] * grid.count[1] * grid.count[2], xyz = new Float32Array(3 * P), p = [0, 0, 0];
  for (let r = 0; r < P; ++r) xyz.set(probePosition(grid, r, p), 3 * r);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(new Float32Array(3 * P), 3));
  const points = new THREE.Points(g, new THREE.PointsMaterial({ size: 5, sizeAttenuation: false, vertexColors: true }));
  points.frustumCulled = false;
  points.visible = false;
  return points;
}

/**
 * The GPU side of a probe bake `b` (probe_bake.js): { bake, meshes (the scene's parts, the ball,
 * the probe points), probes: { relighter, ball: { centre, radius }, frame(f) } }. frame(f)
 * brings it up to date for f = { transfer, bands, rotation (rows), light (B² × 3), at (the
 * ball's centre), showProbes }.
 */
export function uploadProbeScene(b) {
  const relighter = new ProbeRelighter(b.grid);
  const parts = b.parts.map((p) => radianceMesh(p.geometry, pageRadianceMaterial()));
  const ball = ballDefaults(b.grid);
  const sphere = new THREE.SphereGeometry(ball.radius, 64, 32);
  const V = sphere.getAttribute('position').count;
  const object = radianceMesh(sphere, pageRadianceMaterial(), new Float32Array(3 * V).fill(defaultAlbedo));
  const placed = new Float32Array(3 * V);
  const points = probePoints(b.grid);
  let at = null;

  const shade = (m, positions) => shadeRadianceMesh(m, relighter, positions);
  const colourPoints = () => {
    const c = points.geometry.getAttribute('color'), L = relighter.lighting, k = L.bands * L.bands * 3;
    for (let r = 0; r < c.count; ++r)
      for (let ch = 0; ch < 3; ++ch) c.array[3 * r + ch] = Math.max(L.coeffs[r * k + ch] * kY00, 0);
    c.needsUpdate = true;
  };
  function frame(f) {
    const relit = relighter.relight(f.transfer, f.bands, f.rotation, f.light);
    if (relit) {
      parts.forEach((m) => shade(m));
      colourPoints();
    }
    if (relit || !at || f.at.some((x, a) => x !== at[a])) {
      at = f.at.slice();
      for (let v = 0; v < V; ++v)
        for (let a = 0; a < 3; ++a) placed[3 * v + a] = object.positions[3 * v + a] + at[a];
      shade(object, placed);
      object.mesh.position.fromArray(at);
    }
    points.visible = !!f.showProbes;
  }
  return { bake: b, meshes: [...parts.map((m) => m.mesh), object.mesh, points],
           probes: { relighter, ball, frame, sphere: object.mesh } };
}

/** Frees the materials uploadProbeScene made (the geometries are the meshes' to free). */
export function disposeProbeScene(gpu) {
  for (const m of gpu.meshes) m.material.dispose();
}
