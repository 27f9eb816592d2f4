// The relightable bake the loader plugin (plugin.js) leaves in gltf.userData.prtkit: the parts
// of the glTF scene wear prtkit materials (web/src/draw.js with the three host), and this object
// holds what a frame needs — the light, its rotation, the exposure, the transfer and bands
// shown — and does each frame's work from the meshes' onBeforeRender, so an app only renders
// its scene. The environment stays fixed in the world: turning or moving the bake's scene turns
// the light the other way in the bake's frame, and glossy transfer sees the camera from where
// the part is (rigid motions and uniform scale).
import * as THREE from 'three';
import { checkedBands, exposureScale, transferLight } from './relight_settings.js';
import { pickTransfer } from '../../src/transfer.js';
import { disposeTransfers, setFrameLight, setTransferUniforms, uploadTransfers } from '../../src/draw.js';
import { mul3, transpose3 } from '../../src/sh.js';
import { threeHost } from './three_host.js';
import { rotationRows } from './rotation.js';

const tmpVector = new THREE.Vector3(), tmpScale = new THREE.Vector3(), tmpMatrix = new THREE.Matrix4(),
  tmpQuat = new THREE.Quaternion();

export class PRTBake {
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
    this._transfer = pickTransfer(this._gpu.bake.transfers, mode);
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
    this._meshes.forEach((mesh, p) => { mesh.material = this._gpu.parts[p].materials[this._transfer.key]; });
    ++this._version;
  }

  /** The light in the bake's frame: R = Q_rootᵀ Q_light (row-major). The root's world matrix is
   *  brought up to date here: a part's onBeforeRender may run before its ancestors' update. */
  _bakeRotation() {
    this.root.updateWorldMatrix(true, false);
    this.root.matrixWorld.decompose(tmpVector, tmpQuat, tmpScale);
    return mul3(transpose3(rotationRows(tmpQuat)), rotationRows(this.lightRotation));
  }

  _beforeRender(p, camera) {
    const t = this._transfer;
    // Every part of a frame asks; the light (and CPCA's cluster table) is made once, when the
    // light, its rotation, the bake's placement, the transfer or the bands changed.
    const R = this._bakeRotation(), last = this._last;
    const flat = R.flat();
    if (!last || last.version !== this._version || flat.some((x, i) => x !== last.rotation[i])) {
      setFrameLight(this._gpu, t, this._bands, R, this._coeffs || new Float32Array(t.bands * t.bands * 3));
      this._last = { version: this._version, rotation: flat };
    }
    // The eye in the part's frame (glossy transfer's view; unused otherwise).
    const mesh = this._meshes[p];
    const eye = camera.getWorldPosition(tmpVector).applyMatrix4(tmpMatrix.copy(mesh.matrixWorld).invert());
    setTransferUniforms(this._gpu, p, t, { bands: this._bands, eye });
    mesh.material.uniformsNeedUpdate = true;
  }
}
