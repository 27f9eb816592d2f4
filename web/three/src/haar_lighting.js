// A Haar bake in three.js (prt bake --basis haar; docs/haar.md, docs/three.md "Haar bakes"): the
// loader plugin leaves a HaarLighting in gltf.userData.prtkit, its meshes dressed in materials
// drawn from per-vertex radiance (the three host's radiance stage), or per texel from a relit
// lightmap fetched per pixel (web/src/haar_texels.js; the texel points prt web writes beside
// its bake come as the plugin's texelPoints option). The radiance is made on the
// CPU, as prt render and the page make it: the light's K largest wavelet terms (web/src/
// haar_light.js) and each vertex's sparse terms (haar_relight.js) — an inter-reflected
// transfer's bounce against the light's full SH (haarLightFullSh, made with the light) — again
// whenever the light, its rotation (or the bake's placement), the terms or the transfer change.
//
// The light is either an environment's cube (haarEnvironment: what prt web writes beside each
// environment of a Haar bake's page), which turns — the environment is resampled at each
// rotation, as Haar wavelets do not rotate — or a Haar light file (parseHaarLight: prt light
// --basis haar), made for one rotation, which refuses any other.
import * as THREE from 'three';
import { haar as kHaar } from 'prt:constants';
import { exposureScale } from './relight_settings.js';
import { pickTransfer } from '../../src/transfer.js';
import { mul3, transpose3 } from '../../src/sh.js';
import { base64Bytes, decodeRgbe } from '../../src/environment.js';
import { environmentCube, parseHaarLight, turnedLight } from '../../src/haar_light.js';
import { relightHaar } from '../../src/haar_relight.js';
import { radianceMesh } from '../../src/radiance_mesh.js';
import { haarTexelDrawing } from '../../src/haar_texels.js';
import { threeHost } from './three_host.js';
import { rotationRows } from './rotation.js';

const identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
const tmpVector = new THREE.Vector3(), tmpScale = new THREE.Vector3(), tmpQuat = new THREE.Quaternion();

/** An environment's cube for Haar bakes, from prt web's data (prt-data.js: environments[i].haar,
 *  { resolution, rgbe (base64), sh }): HaarLighting.setLight's turning light. */
export function haarEnvironment(entry, name = 'environment') {
  if (!entry || !Number.isInteger(entry.resolution) || typeof entry.rgbe !== 'string' || !Array.isArray(entry.sh))
    throw new Error(`${name}: a Haar environment is prt web's { resolution, rgbe, sh } (prt-data.js, environments[i].haar)`);
  return { isHaarEnvironment: true, name, ...environmentCube(entry.resolution, base64Bytes(entry.rgbe), entry.sh, name, decodeRgbe) };
}

export { parseHaarLight };

export class HaarLighting {
  /** (Made by the loader plugin.) bake: web/src/haar_bake.js's readHaarBake result; root: the
   *  glTF scene. */
  constructor(bake, root, limits = { maxTextureSize: 4096 }) {
    /** Type test: a Haar bake's lighting (an SH bake gives a PRTBake). */
    this.isHaarLighting = true;
    this.name = bake.name;
    this.root = root;
    /** The light's rotation in the world (THREE.Quaternion; set it, or mutate it, any time). */
    this.lightRotation = new THREE.Quaternion();
    this._bake = bake;
    this._transfer = pickTransfer(bake.transfers, '');
    this._terms = kHaar.defaultLightTerms;
    this._source = null;
    this._made = null;  // { key, light }
    this._exposure = { value: 1 };
    // Per texel: the relit lightmap drawn per pixel (web/src/haar_texels.js).
    this._texels = bake.lightmap ? haarTexelDrawing(bake, limits, threeHost(this._exposure)) : null;
    this._dressed = this._dress();
  }

  /** The transfers the bake holds (in the library's preference order). */
  get transfers() {
    return this._bake.transfers.map((t) => ({ mode: t.mode, layout: t.layout, basis: 'haar', resolution: t.haar.resolution,
                                              terms: t.haar.terms, bounceBands: t.haar.bounceBands, channels: t.channels }));
  }
  /** The bake's meshes (they wear a material drawn from their relit radiance). */
  get meshes() { return this._dressed.map((d) => d.m.mesh); }
  /** The transfer relit ('unshadowed', 'shadowed', 'interreflected': the Haar rows and their
   *  bounce in SH; one the bake lacks gives the library's pick). */
  get mode() { return this._transfer.mode; }
  set mode(mode) { this._transfer = pickTransfer(this._bake.transfers, mode); }
  /** The light's wavelet terms K (default 200), 1 .. 6 N². */
  get terms() { return this._terms; }
  set terms(k) {
    if (!(Number.isInteger(k) && k >= 1)) throw new Error(`${this.name}: terms must be a positive integer, not ${k}`);
    this._terms = k;
  }
  /** Exposure in stops of the bake's own meshes (2^exposure before the renderer's tone map). */
  get exposure() { return Math.log2(this._exposure.value); }
  set exposure(stops) { this._exposure.value = exposureScale(this.name, stops); }
  /** The light as given, and the light last relit with ({ index, value, energyKept, ... }). */
  get light() { return this._source; }
  get relitLight() { return this._made && this._made.light; }

  /** Relights under `source`: haarEnvironment(...) (turns) or parseHaarLight(...) (fixed), over
   *  the transfer's cube. Returns the warnings (none). */
  setLight(source) {
    const n = this._transfer.haar.resolution;
    if (source && source.isHaarEnvironment) {
      if (source.resolution !== kHaar.fineCubeFactor * n)
        throw new Error(`${this.name}: ${source.name}'s cube is ${source.resolution}² a face, for Haar bakes over ${source.resolution / kHaar.fineCubeFactor}² cubes; this bake's is ${n}²`);
    } else if (source && source.fixed) {
      if (source.resolution !== n)
        throw new Error(`${this.name}: the Haar light is over a ${source.resolution}² cube, the bake's transfer over ${n}² (prt light --basis haar --resolution ${n})`);
    } else {
      throw new Error(`${this.name}: a Haar bake is relit by haarEnvironment(...) (prt web's environment cube) or parseHaarLight(...) (prt light --basis haar)`);
    }
    this._source = source;
    this._made = null;
    return [];
  }

  /** Relights the meshes if the light, its rotation (or the bake's placement), the terms or the
   *  mode changed since the last call; returns whether it did. The meshes call it before they
   *  draw. */
  update() {
    if (!this._source) throw new Error(`${this.name}: no light yet (setLight)`);
    const R = this._lightInBake(), t = this._transfer, n = t.haar.resolution;
    const key = [t.key, this._terms, ...R.flat()].join(' ');
    if (this._made && this._made.key === key) return false;
    let light = this._source;
    if (this._source.isHaarEnvironment) {
      light = turnedLight(this._source, n, this._terms, R);
    } else if (R.some((row, i) => row.some((x, j) => Math.abs(x - identity[i][j]) > 1e-12))) {
      throw new Error(`${this.name}: a Haar light file cannot be turned (the environment is resampled at each rotation: give haarEnvironment(...))`);
    }
    if (this._texels) {
      this._texels.relight(t, light);
      this._dressed.forEach((d, i) => { d.m.mesh.material = this._texels.material(i, t); });
    } else {
      for (const d of this._dressed) {
        relightHaar(t, light, d.m.normals, t.kd || d.m.albedo, d.m.radiance.array, d.part.first, d.part.vertices);
        d.m.radiance.needsUpdate = true;
      }
    }
    this._made = { key, light };
    return true;
  }

  /** Frees the materials (the meshes stay in the scene). */
  dispose() {
    for (const d of this._dressed) {
      d.m.mesh.onBeforeRender = () => {};
      if (!this._texels) d.m.mesh.material.dispose();
    }
    if (this._texels) this._texels.dispose();
  }

  /** The bake's parts in materials drawn from their per-vertex radiance, or per texel from the
   *  relit lightmap. */
  _dress() {
    const host = threeHost(this._exposure);
    return this._bake.parts.map((part, i) => {
      if (this._texels) {
        const mesh = part.mesh;
        mesh.material = this._texels.material(i, this._transfer);
        mesh.frustumCulled = false;
        mesh.onBeforeRender = () => { if (this._source) this.update(); };
        return { part, m: { mesh } };
      }
      const material = host.material({ vertexShader: host.stages['radiance.vert'], fragmentShader: host.stages.fragment,
                                       defines: {}, uniforms: { uExposureScale: this._exposure }, hasAlbedo: false });
      const m = radianceMesh(part.geometry, material, null, part.mesh);
      m.mesh.onBeforeRender = () => { if (this._source) this.update(); };
      return { part, m };
    });
  }

  /** The light's rotation in the bake's frame: R = Q_rootᵀ Q_light (row-major). */
  _lightInBake() {
    this.root.updateWorldMatrix(true, false);
    this.root.matrixWorld.decompose(tmpVector, tmpQuat, tmpScale);
    return mul3(transpose3(rotationRows(tmpQuat)), rotationRows(this.lightRotation));
  }
}
