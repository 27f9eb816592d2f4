// The relightable bake the loader plugin (plugin.js) leaves in gltf.userData.prtkit: the parts
// of the glTF scene wear prtkit materials (web/src/draw.js with the three host), and this object
// holds what a frame needs — the light, its rotation, the exposure, the transfer and bands
// shown — and does each frame's work from the meshes' onBeforeRender, so an app only renders
// its scene. The environment stays fixed in the world: turning or moving the bake's scene turns
// the light the other way in the bake's frame, and glossy transfer sees the camera from where
// the part is (rigid motions and uniform scale). A matrix transfer can be drawn through an
// engine's irradiance encoding instead (`encoding`, as prt render --encoding: its diffuse part,
// kd ⊙ Ê(n)/π per vertex made on the CPU, web/src/encoded_diffuse.js); dense matrices are drawn
// only so (through l2 unless an encoding is chosen).
import * as THREE from 'three';
import { checkedBands, checkedEncoding, exposureScale, transferLight } from './relight_settings.js';
import { pickTransfer } from '../../src/transfer.js';
import { shownEncoding } from '../../src/encoded_diffuse.js';
import { encodingNames } from '../../src/irradiance_encoding.js';
import { disposeTransfers, setEncodedRadiance, setFrameLight, setTransferUniforms, transferMaterialOf,
  uploadTransfers } from '../../src/draw.js';
import { mul3, transpose3 } from '../../src/sh.js';
import { threeHost } from './three_host.js';
import { rotationRows } from './rotation.js';

const tmpVector = new THREE.Vector3(), tmpScale = new THREE.Vector3(), tmpMatrix = new THREE.Matrix4(),
  tmpQuat = new THREE.Quaternion();

export class PRTBake {
  /** The irradiance encodings `encoding` takes besides 'none', in the library's order. */
  static get encodings() { return encodingNames.slice(); }

  /** (Made by the loader plugin.) bake: web/src/bake.js's readBake result; root: the glTF scene. */
  constructor(bake, root, limits) {
    this.name = bake.name;
    this.root = root;
    /** The light's rotation in the world (THREE.Quaternion; set it, or mutate it, any time). */
    this.lightRotation = new THREE.Quaternion();
    this._exposure = { value: 1 };
    this._gpu = uploadTransfers(bake, limits, threeHost(this._exposure));
    this._meshes = bake.parts.map((p) => p.mesh);
    this._light = null;      // the light as given
    this._coeffs = null;     // at the bake's bands (cut or zero-padded)
    this._version = 0;       // bumped when the light, transfer or bands change
    this._last = null;       // { version, rotation } the frame's light was computed for
    this._transfer = pickTransfer(bake.transfers, '');
    this._bands = this._transfer.bands;
    this._encoding = 'none';
    this._meshes.forEach((mesh, p) => {
      mesh.onBeforeRender = (renderer, scene, camera) => this._beforeRender(p, camera);
    });
    this._wear();
  }

  /** The transfers the bake holds (in the library's preference order). */
  get transfers() {
    return this._gpu.bake.transfers.map((t) => ({ mode: t.mode, layout: t.layout, bands: t.bands, channels: t.channels,
                                                  compressed: !!t.compressed, path: t.describe }));
  }
  /** The meshes that wear prtkit materials (the glTF's parts). */
  get meshes() { return this._meshes.slice(); }

  /** The transfer mode shown ('unshadowed', 'shadowed', 'interreflected'); setting one the bake
   *  lacks shows the library's pick (io::pickTransfer). */
  get mode() { return this._transfer.mode; }
  set mode(mode) {
    const t = pickTransfer(this._gpu.bake.transfers, mode);
    checkedEncoding(this._gpu.bake, t, this._encoding);  // the encoding stays: t must take it
    this._transfer = t;
    this._bands = Math.min(this._bands, this._transfer.bands) || this._transfer.bands;
    this._light && this.setLight(this._light);
    this._wear();
  }
  /** The bands shown, 1 .. the transfer's. */
  get bands() { return this._bands; }
  set bands(b) {
    this._bands = checkedBands(this.name, b, this._transfer.bands);
    ++this._version;
  }
  /**
   * The irradiance encoding a matrix transfer is drawn through, as `prt render --encoding`:
   * 'none' (PRT's own radiance, the default) or one of the library's encodings ('l1',
   * 'l1-windowed', 'l1-geomerics', 'zh3-hallucinated', 'zh3', 'zh3-shared', 'zh3-optimal',
   * 'l2', 'l2-deringed'): the diffuse part kd ⊙ Ê(n)/π per vertex, Ê the encoded irradiance of the
   * light arriving there, made on the CPU when the light, its rotation, the bands or the encoding
   * change. A vector or per-texel transfer refuses a name (one line naming the bake).
   */
  get encoding() { return this._encoding; }
  set encoding(name) {
    this._encoding = checkedEncoding(this._gpu.bake, this._transfer, name);
    this._wear();
  }
  /** The encoding the transfer shown is drawn through: `encoding`, 'l2' for dense matrices
   *  when it is 'none' (the browser viewers draw those on the CPU only), else 'none'. */
  get shownEncoding() { return shownEncoding(this._transfer, this._encoding) || 'none'; }
  /** Exposure in stops: the radiance is scaled by 2^exposure before the renderer's tone map. */
  get exposure() { return Math.log2(this._exposure.value); }
  set exposure(stops) {
    this._exposure.value = exposureScale(this.name, stops);
  }
  get light() { return this._light; }

  /**
   * Relights under `light` ({ bands, coeffs: B² × 3 } from parseLight or
   * lightFromSphericalHarmonics3). A light with more bands than the transfer is cut (exactly);
   * one with fewer is used as it is, and the returned warnings say so (the library's rule).
   */
  setLight(light) {
    const { coeffs, warnings } = transferLight(this.name, light, this._transfer.bands);
    this._light = light;
    this._coeffs = coeffs;
    ++this._version;
    return warnings;
  }

  /** Frees the GPU objects (textures, materials); the meshes keep their geometry. */
  dispose() {
    for (const m of this._meshes) m.onBeforeRender = () => {};
    disposeTransfers(this._gpu);
  }

  _wear() {
    this._meshes.forEach((mesh, p) => { mesh.material = transferMaterialOf(this._gpu, p, this._transfer, this._encoding); });
    ++this._version;
  }

  /** The light in the bake's frame: R = Q_rootᵀ Q_light (row-major). The root's world matrix is
   *  brought up to date here: a part's onBeforeRender may run before its ancestors' update. */
  _bakeRotation() {
    this.root.updateWorldMatrix(true, false);
    this.root.matrixWorld.decompose(tmpVector, tmpQuat, tmpScale);
    return mul3(transpose3(rotationRows(tmpQuat)), rotationRows(this.lightRotation));
  }

  /**
   * Brings the frame's light up to date (and CPCA's cluster table, and an encoded transfer's
   * radiance per vertex) if the light, its rotation, the bake's placement, the transfer, the bands
   * or the encoding changed since the last call; returns whether it did. The meshes call it
   * before they draw. An encoded transfer's radiance is a vertex attribute, which three.js
   * uploads before the meshes' onBeforeRender: call update() before renderer.render for a frame
   * to show a change at once (else it shows from the next frame on).
   */
  update() {
    const t = this._transfer;
    // Every part of a frame asks; the light (and CPCA's cluster table) is made once, when the
    // light, its rotation, the bake's placement, the transfer or the bands changed.
    const R = this._bakeRotation(), last = this._last;
    const flat = R.flat();
    if (last && last.version === this._version && flat.every((x, i) => x === last.rotation[i])) return false;
    setFrameLight(this._gpu, t, this._bands, R, this._coeffs || new Float32Array(t.bands * t.bands * 3));
    setEncodedRadiance(this._gpu, t, this._bands, this._encoding);
    this._last = { version: this._version, rotation: flat };
    return true;
  }

  _beforeRender(p, camera) {
    const t = this._transfer;
    this.update();
    // The eye in the part's frame (glossy transfer's view; unused otherwise).
    const mesh = this._meshes[p];
    const eye = camera.getWorldPosition(tmpVector).applyMatrix4(tmpMatrix.copy(mesh.matrixWorld).invert());
    setTransferUniforms(this._gpu, p, t, { bands: this._bands, eye, encoding: this._encoding });
    mesh.material.uniformsNeedUpdate = true;
  }
}
