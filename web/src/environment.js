// The page's environments: each an SH light (the bake's bands, as prt web projected it, or a
// dropped light file) and its lat-long background — prt web's RGBE image, else the light's SH
// reconstruction (envmap::renderSh) — as half-float textures for shaders/stages/background.frag.
import * as THREE from 'three';

import { evalSh } from './sh.js';
import { lightForTransfer } from './lights.js';

export function base64Bytes(b64) {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out;
}

export function bytesBase64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

/** Radiance RGBE bytes (prt web's backgrounds) to float RGB: (m + 0.5) · 2^(e − 136). */
export function decodeRgbe(bytes) {
  const n = bytes.length / 4, rgb = new Float32Array(n * 3);
  for (let p = 0; p < n; ++p) {
    const e = bytes[4 * p + 3];
    if (e === 0) continue;
    const f = Math.pow(2, e - 136);
    rgb[3 * p] = (bytes[4 * p] + 0.5) * f;
    rgb[3 * p + 1] = (bytes[4 * p + 1] + 0.5) * f;
    rgb[3 * p + 2] = (bytes[4 * p + 2] + 0.5) * f;
  }
  return rgb;
}

/** A float RGB lat-long image as a filterable half-float RGBA texture (wraps in u). */
export function latLongTexture(width, height, rgb) {
  // Half floats end at 65504: a sun's radiance is clamped there (invisible after any tone map
  // unless the exposure is below about −12 stops).
  const half = new Uint16Array(width * height * 4);
  const h = (v) => THREE.DataUtils.toHalfFloat(Math.min(Math.max(v, 0), 65504));
  for (let p = 0, n = width * height; p < n; ++p) {
    half[4 * p] = h(rgb[3 * p]);
    half[4 * p + 1] = h(rgb[3 * p + 1]);
    half[4 * p + 2] = h(rgb[3 * p + 2]);
    half[4 * p + 3] = 0x3c00;
  }
  const t = new THREE.DataTexture(half, width, height, THREE.RGBAFormat, THREE.HalfFloatType);
  t.wrapS = THREE.RepeatWrapping;
  t.wrapT = THREE.ClampToEdgeWrapping;
  t.minFilter = t.magFilter = THREE.LinearFilter;
  t.generateMipmaps = false;
  t.colorSpace = THREE.NoColorSpace;
  t.needsUpdate = true;
  return t;
}

/** Σ_i L_i Y_i(d) over a width × width/2 lat-long (envmap::renderSh), clamped at zero. */
export function shImage(bands, coeffs, width = 128) {
  const h = width / 2, rgb = new Float32Array(width * h * 3), y = new Float64Array(bands * bands);
  for (let j = 0; j < h; ++j)
    for (let i = 0; i < width; ++i) {
      const theta = ((j + 0.5) / h) * Math.PI, phi = ((i + 0.5) / width - 0.5) * 2 * Math.PI;
      evalSh(bands, Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi), y);
      for (let c = 0; c < 3; ++c) {
        let s = 0;
        for (let k = 0; k < bands * bands; ++k) s += y[k] * coeffs[3 * k + c];
        rgb[(j * width + i) * 3 + c] = s;
      }
    }
  return latLongTexture(width, h, rgb);
}

/** An environment: `light` = { bands, coeffs } as given; `background` prt web's (or null);
 *  `haarSource` the cube prt web writes for a Haar bake's page ({ resolution, rgbe, sh }: the
 *  light haar_scene.js turns; null for an SH light). */
export function environment(name, light, background, haarSource = null) {
  return { name, source: light, background, coeffs: null, bands: 0, texture: null, shCache: null, haarSource, haarCube: null };
}

/** Fits environment e to a transfer of `bands` bands (lights.js: cut or padded, with the
 *  library's warning); returns the warnings. */
export function fitEnvironment(e, bands) {
  const l = lightForTransfer(e.name, e.source, bands);
  e.coeffs = l.coeffs;
  e.bands = bands;
  if (e.shCache) e.shCache.texture.dispose(), e.shCache = null;
  return l.warnings;
}

/** The background texture of e: its image, or (background 'sh') its SH at `bands`. */
export function backgroundTexture(e, mode, bands) {
  if (mode === 'sh') {
    if (!e.shCache || e.shCache.bands !== bands) {
      if (e.shCache) e.shCache.texture.dispose();
      e.shCache = { bands, texture: shImage(bands, e.coeffs) };
    }
    return e.shCache.texture;
  }
  if (!e.texture) {
    const bg = e.background;
    e.texture = bg && bg.rgbe ? latLongTexture(bg.width, bg.height, decodeRgbe(base64Bytes(bg.rgbe)))
      : shImage(e.source.bands, e.source.coeffs);  // a dropped SH light: its reconstruction
  }
  return e.texture;
}
