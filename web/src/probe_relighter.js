// A probe grid kept relit: what both the page's probe mode (probe_scene.js) and prtkit-three's
// ProbeGridLighting hold. It relights (probe_lighting.js) only when what the light arriving at
// the probes depends on changed — the transfer shown, the bands, the light's coefficients or its
// rotation — so a frame whose light stands still costs nothing, and a turning light one
// B²·B² product per probe and channel (plus the rotation of the light, sh.js).
import { rotateLight } from './sh.js';
import { relightProbes, sampleProbes, shadeVertices } from './probe_lighting.js';

export class ProbeRelighter {
  /** grid: a probe bake's { origin, spacing, count } (probe_bake.js). */
  constructor(grid) {
    this.grid = grid;
    this.lighting = null;  // relightProbes' result for the inputs in _inputs
    this._inputs = null;
  }

  /**
   * Relights under the light `coeffs` (our basis, B² × 3, B ≥ b: a light with fewer bands is
   * padded first, lights.js) turned by R (row-major 3 × 3; L'(ω) = L(Rᵀω), the light rotated on
   * its coefficients as the library does) with the first b bands of probe transfer t. Returns
   * whether it relit (false: the inputs are the last call's).
   */
  relight(t, b, R, coeffs) {
    const flat = R.flat(), last = this._inputs;
    if (last && last.t === t && last.b === b && last.coeffs === coeffs && flat.every((x, i) => x === last.R[i])) return false;
    const bands = Math.min(b, t.bands);
    this.lighting = relightProbes(t, this.grid, rotateLight(bands, R, coeffs), bands, this.lighting && this.lighting.coeffs);
    this._inputs = { t, b, coeffs, R: flat };
    return true;
  }

  /** The relit incident SH (b² RGB coefficients, our basis) at a point, trilinear, clamped. */
  incidentAt(x, y, z, out) {
    return sampleProbes(this.lighting, x, y, z, out);
  }

  /** ρ E(n)/π per vertex through the relit grid (render::shadeThroughProbes). */
  shadeVertices(positions, normals, albedo, out) {
    return shadeVertices(this.lighting, positions, normals, albedo, out);
  }
}
