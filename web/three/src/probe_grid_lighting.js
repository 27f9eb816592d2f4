// A probe bake in three.js (docs/three.md, "Probe grids"; docs/probes.md): the loader plugin
// leaves one of these in gltf.userData.prtkit for a file `prt probes` wrote. It keeps the grid
// relit under a light and its rotation (web/src/probe_relighter.js: L'_p = M_p L per probe and
// channel, the light turned on its coefficients as the library turns it), and answers for any
// point the light arriving there (the trilinear blend of its eight probes, clamped to the grid),
// the diffuse shading of a normal there (ρ E(n)/π), a three.js LightProbe at a moving object,
// and the whole grid as data (irradiance_volume.js). The bake's own meshes wear a material that
// shows them lit through the grid, as prt render draws a probe bake.
//
// Frames: the grid lies in the bake's glTF scene (`root`). Points and normals given here are in
// the world; the light stays in the world (lightRotation turns it there), so moving or turning
// the bake's scene moves the grid with it and turns the light the other way in its frame, as
// for PRTBake. Rigid motions and uniform scale only.
import * as THREE from 'three';
import { checkedBands, checkedEncoding, exposureScale, transferLight } from './relight_settings.js';
import { pickTransfer } from '../../src/transfer.js';
import { mul3, rotateLight as rotateCoefficients, transpose3 } from '../../src/sh.js';
import { ProbeRelighter } from '../../src/probe_relighter.js';
import { probePosition, shadeDiffuse } from '../../src/probe_lighting.js';
import { radianceMesh, shadeRadianceMesh } from '../../src/radiance_mesh.js';
import { lightToSphericalHarmonics3 } from './light.js';
import { rotationRows } from './rotation.js';
import { threeHost } from './three_host.js';
import { irradianceVolumeJson, lightProbeGridParameters } from './irradiance_volume.js';

const tmpVector = new THREE.Vector3(), tmpScale = new THREE.Vector3(), tmpQuat = new THREE.Quaternion();
const identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];

export class ProbeGridLighting {
  /** (Made by the loader plugin.) bake: web/src/bake.js's readBake result for a probe bake;
   *  root: the glTF scene. */
  constructor(bake, root) {
    /** Type test: a probe bake's lighting (a surface bake gives a PRTBake). */
    this.isProbeGridLighting = true;
    this.name = bake.name;
    this.root = root;
    /** The light's rotation in the world (THREE.Quaternion; set it, or mutate it, any time). */
    this.lightRotation = new THREE.Quaternion();
    this._bake = bake;
    this._relighter = new ProbeRelighter(bake.grid);
    this._transfer = pickTransfer(bake.transfers, '');
    this._bands = this._transfer.bands;
    this._light = null;
    this._coeffs = null;
    this._exposure = { value: 1 };
    this._dressed = this._dress();
  }

  /** The grid in the bake's frame: { origin, spacing, count } (arrays of three). */
  get grid() { return { origin: this._bake.grid.origin.slice(), spacing: this._bake.grid.spacing.slice(), count: this._bake.grid.count.slice() }; }
  /** The transfers the bake holds (in the library's preference order). */
  get transfers() {
    return this._bake.transfers.map((t) => ({ mode: t.mode, layout: t.layout, bands: t.bands, channels: t.channels, compressed: t.compressed }));
  }
  /** The bake's meshes (they wear a material lit through the grid). */
  get meshes() { return this._dressed.map((d) => d.mesh); }
  /** The transfer relit ('unshadowed', 'shadowed', 'interreflected'; one the bake lacks gives the
   *  library's pick). */
  get mode() { return this._transfer.mode; }
  set mode(mode) {
    this._transfer = pickTransfer(this._bake.transfers, mode);
    this._bands = Math.min(this._bands, this._transfer.bands);
    if (this._light) this.setLight(this._light);
  }
  /** The bands relit, 1 .. the transfer's. */
  get bands() { return this._bands; }
  set bands(b) {
    this._bands = checkedBands(this.name, b, this._transfer.bands);
  }
  /** 'none': an irradiance encoding (PRTBake's `encoding`) draws a surface's matrix transfer;
   *  setting one here is refused in one line naming the bake. */
  get encoding() { return 'none'; }
  set encoding(name) {
    checkedEncoding(this._bake, this._transfer, name);
  }
  /** Exposure in stops of the bake's own meshes (2^exposure before the renderer's tone map). */
  get exposure() { return Math.log2(this._exposure.value); }
  set exposure(stops) {
    this._exposure.value = exposureScale(this.name, stops);
  }
  get light() { return this._light; }

  /** Relights under `light` ({ bands, coeffs: B² × 3 }, parseLight's); the library's band rule
   *  (more bands cut, fewer used as they are: the returned warnings say so). */
  setLight(light) {
    const { coeffs, warnings } = transferLight(this.name, light, this._transfer.bands);
    this._light = light;
    this._coeffs = coeffs;
    return warnings;
  }

  /**
   * Relights the grid if the light, its rotation (or the bake's placement), the mode or the bands
   * changed since the last call; returns whether it did. Every query calls it; the bake's meshes
   * call it before they draw.
   */
  update() {
    if (!this._coeffs) throw new Error(`${this.name}: no light yet (setLight)`);
    const relit = this._relighter.relight(this._transfer, this._bands, this._lightInBake(), this._coeffs);
    if (relit) for (const d of this._dressed) shadeRadianceMesh(d, this._relighter);
    return relit;
  }

  /**
   * The SH of the light arriving at `point` (a THREE.Vector3 in the world): { bands, coeffs:
   * Float64Array(b² × 3) } in prtkit's basis (parseLight's), turned into the world. Outside the
   * grid, the nearest face's probes.
   */
  incidentAt(point) {
    this.update();
    const p = this._toBake(point), coeffs = this._relighter.incidentAt(p.x, p.y, p.z);
    const b = this._relighter.lighting.bands;
    const Q = this._rootRotation();
    return { bands: b, coeffs: Q === identity ? coeffs : rotateCoefficients(b, Q, coeffs, new Float64Array(coeffs.length)) };
  }

  /** The diffuse exit radiance ρ E(n)/π at `point` with unit world normal `normal` (Vector3s)
   *  and albedo ρ (a THREE.Color, default white): a THREE.Color of linear radiance. */
  shadeAt(point, normal, albedo = new THREE.Color(1, 1, 1), target = new THREE.Color()) {
    const { bands, coeffs } = this.incidentAt(point);
    const rgb = shadeDiffuse(coeffs, bands, normal.x, normal.y, normal.z, [albedo.r, albedo.g, albedo.b]);
    return target.setRGB(rgb[0], rgb[1], rgb[2]);
  }

  /**
   * Sets `probe` (a THREE.LightProbe) to the light arriving at `position` (a Vector3 in the
   * world; default the probe's own world position): its first three bands in three.js's basis
   * (lightToSphericalHarmonics3; a transfer of fewer bands is zero-padded). Call it each frame
   * for a moving object; its intensity is left to you. Returns the probe.
   */
  updateLightProbe(probe, position = probe.getWorldPosition(new THREE.Vector3())) {
    lightToSphericalHarmonics3(this.incidentAt(position), probe.sh);
    return probe;
  }

  /**
   * The relit grid as plain data, in the bake's frame: the JSON object `prt export --format
   * probe-grid --engine threejs` writes (irradiance_volume.js: per probe the nine RGB
   * coefficients of three.js's SphericalHarmonics3, LightProbeGrid's parameters and atlas) and
   * every probe's position. `light` names the light in it.
   */
  irradianceVolume(light = 'light') {
    this.update();
    const L = this._relighter.lighting, k = L.bands * L.bands * 3, sh = new THREE.SphericalHarmonics3();
    // The light's rotation in the bake's frame as prt's --rotate X,Y,Z (R = Rz Ry Rx: 'ZYX').
    const R = this._lightInBake(), m = new THREE.Matrix4();
    m.set(R[0][0], R[0][1], R[0][2], 0, R[1][0], R[1][1], R[1][2], 0, R[2][0], R[2][1], R[2][2], 0, 0, 0, 0, 1);
    const e = new THREE.Euler().setFromRotationMatrix(m, 'ZYX');
    return irradianceVolumeJson(this._bake.grid, (p, out) => {
      lightToSphericalHarmonics3({ bands: L.bands, coeffs: L.coeffs.subarray(p * k, (p + 1) * k) }, sh);
      sh.toArray(out);
    }, (p, out) => probePosition(this._bake.grid, p, out), {
      generator: 'prtkit-three (ProbeGridLighting.irradianceVolume)', source: this.name, light,
      rotateDegrees: [e.x, e.y, e.z].map(THREE.MathUtils.radToDeg),
    });
  }

  /** three.js r187's LightProbeGrid parameters for this grid (irradiance_volume.js). */
  lightProbeGridParameters() {
    return lightProbeGridParameters(this._bake.grid);
  }

  /** Frees the meshes' materials (the geometry stays the meshes'). */
  dispose() {
    for (const d of this._dressed) {
      d.mesh.onBeforeRender = () => {};
      d.mesh.material.dispose();
    }
  }

  /** The bake's parts in materials drawn from their per-vertex radiance through the grid. */
  _dress() {
    const host = threeHost(this._exposure);
    return this._bake.parts.map((p) => {
      const material = host.material({ vertexShader: host.stages['radiance.vert'], fragmentShader: host.stages.fragment,
                                       defines: {}, uniforms: { uExposureScale: this._exposure }, hasAlbedo: false });
      const d = radianceMesh(p.geometry, material, null, p.mesh);
      d.mesh.onBeforeRender = () => { if (this._coeffs) this.update(); };
      return d;
    });
  }

  /** The root's rotation (row-major), or `identity` itself when it has none. */
  _rootRotation() {
    this.root.updateWorldMatrix(true, false);
    this.root.matrixWorld.decompose(tmpVector, tmpQuat, tmpScale);
    const Q = rotationRows(tmpQuat);
    return Q.every((row, i) => row.every((x, j) => x === identity[i][j])) ? identity : Q;
  }

  /** The light's rotation in the bake's frame: R = Q_rootᵀ Q_light (row-major). */
  _lightInBake() {
    return mul3(transpose3(this._rootRotation()), rotationRows(this.lightRotation));
  }

  /** A world point in the bake's frame. */
  _toBake(point) {
    this.root.updateWorldMatrix(true, false);
    return this.root.worldToLocal(new THREE.Vector3().copy(point));
  }
}
