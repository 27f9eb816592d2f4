// The GPU side of a transfer, by path (transfer.js decides the path once): the stage that
// draws it (shaders/stages/), its uniforms, what each frame sets — as the desktop viewer's
// renderer does per path — and the per-frame light and cluster table every material of a bake
// shares. The stages come flattened for a host (cmake/Shaders.cmake): the page's (webgl2,
// RawShaderMaterial into its HDR target, page_host.js) or the three.js module's (three,
// ShaderMaterial in anyone's scene, web/three). Nothing here touches a scene.
import * as THREE from 'three';
import { bands as kBands } from 'prt:constants';
import { denseTexelsPerRow, frameStep, frameTable } from './transfer.js';
import { rotateLight } from './sh.js';

const kGlossyCoeffs = kBands.maxShaderGlossy * kBands.maxShaderGlossy;

// Compressed glossy matrices (per vertex, or per texel relit per pixel): prt_glossy.glsl's
// uniforms. Each frame: the shaded bands, the table's values per cluster vector (the transfer
// cut to them), the material's kernels, kd (else the albedo), ks, and the camera's eye.
const glossyUniforms = () => ({
  uBands: { value: 1 }, uCoeffs: { value: 1 }, uDiffuse: { value: new Float32Array(kGlossyCoeffs) },
  uGlossy: { value: new Float32Array(kGlossyCoeffs) }, uKd: { value: new THREE.Vector3() },
  uKs: { value: new THREE.Vector3() }, uEye: { value: new THREE.Vector3() }, uHasKd: { value: false },
});
function setGlossy(u, t, f) {
  u.uBands.value = Math.min(f.bands, kBands.maxShaderGlossy);
  u.uCoeffs.value = f.bands * f.bands;
  u.uDiffuse.value.set(t.material.diffuse);
  u.uGlossy.value.set(t.material.lobe);
  u.uHasKd.value = !!t.material.kd;
  if (t.material.kd) u.uKd.value.fromArray(t.material.kd);
  u.uKs.value.fromArray(t.material.ks);
  u.uEye.value.copy(f.eye);
}

const compressedUniforms = () => ({
  uWeights: { value: null }, uClusters: { value: null },
  uTexelsPerVertex: { value: 1 }, uBasisCount: { value: 0 },
});
function setCompressed(u, t, rows, table) {
  u.uWeights.value = rows;
  u.uClusters.value = table;
  u.uTexelsPerVertex.value = t.compressed.texelsPerVertex;
  u.uBasisCount.value = t.compressed.basisCount;
}

// Per-texel transfer (t.perPixel) is drawn per pixel: lightmap.vert passes the lightmap UV and
// the albedo, the host's fragment stage compiled with PRT_LIGHTMAP (and PRT_LIGHTMAP_CPCA)
// fetches the four texels of prt render's bilinear fetch, relights each and blends them
// (shaders/prt_lightmap.glsl) — the same rows and per-frame light or cluster table; CPCA glossy
// matrices (PRT_LIGHTMAP_GLOSSY) shade each tap at its texel's point.
const lightmapUniforms = () => ({ uRows: { value: null }, uLightmapSize: { value: new THREE.Vector2(1, 1) },
                                  uTexelsPerRow: { value: 1 } });
function setLightmap(u, t, f) {
  u.uRows.value = f.rows;
  u.uLightmapSize.value.set(t.lightmap.width, t.lightmap.height);
  u.uTexelsPerRow.value = t.texelsPerRow;
}
const kDrawPerPixel = {
  DenseVector: {
    stage: 'lightmap.vert',
    defines: { PRT_LIGHTMAP: 1 },
    uniforms: (light) => Object.assign(lightmapUniforms(), { uCount: { value: 0 }, uRgb: { value: false }, uL: light }),
    set(u, t, f) {
      setLightmap(u, t, f);
      u.uRgb.value = t.channels === 3;
      u.uCount.value = t.channels === 3 ? f.bands * f.bands : Math.ceil((f.bands * f.bands) / 4);
    },
  },
  CpcaVector: {
    stage: 'lightmap.vert',
    defines: { PRT_LIGHTMAP: 1, PRT_LIGHTMAP_CPCA: 1 },
    uniforms: () => Object.assign(lightmapUniforms(), { uClusters: { value: null }, uBasisCount: { value: 0 } }),
    set(u, t, f) {
      setLightmap(u, t, f);
      u.uClusters.value = f.table;
      u.uBasisCount.value = t.compressed.basisCount;
    },
  },
};
// CPCA glossy matrices per texel: each tap forms its texel's received light from the cluster
// table and shades it at the texel's own point, normal and albedo (uPoints, the bake's
// texelPoints from prt web) — the texel radiance prt render fetches.
kDrawPerPixel.CpcaMatrix = {
  stage: 'lightmap.vert',
  defines: { PRT_LIGHTMAP: 1, PRT_LIGHTMAP_CPCA: 1, PRT_LIGHTMAP_GLOSSY: 1 },
  uniforms: () => Object.assign(kDrawPerPixel.CpcaVector.uniforms(), glossyUniforms(), { uPoints: { value: null } }),
  set(u, t, f) {
    kDrawPerPixel.CpcaVector.set(u, t, f);
    setGlossy(u, t, f);
    u.uPoints.value = f.points;
  },
};
/** How t is drawn: by its path, per pixel for per-texel transfer. */
const drawOf = (t) => (t.perPixel ? kDrawPerPixel : kDraw)[t.path];

const kDraw = {
  DenseVector: {
    stage: 'mesh.vert',
    uniforms: (light) => ({ uTransfer: { value: null }, uTexelsPerVertex: { value: 1 }, uCount: { value: 0 },
                            uRgb: { value: false }, uL: light }),
    set(u, t, f) {
      u.uTransfer.value = f.rows;
      u.uTexelsPerVertex.value = t.texelsPerRow;
      u.uRgb.value = t.channels === 3;
      u.uCount.value = t.channels === 3 ? f.bands * f.bands : Math.ceil((f.bands * f.bands) / 4);
    },
  },
  CpcaVector: {
    stage: 'compressed.vert',
    uniforms: compressedUniforms,
    set: (u, t, f) => setCompressed(u, t, f.rows, f.table),
  },
  CpcaMatrix: {
    stage: 'compressedGlossy.vert',
    uniforms: () => Object.assign(compressedUniforms(), glossyUniforms()),
    set(u, t, f) {
      setCompressed(u, t, f.rows, f.table);
      setGlossy(u, t, f);
    },
  },
};

/**
 * The material that draws transfer t on a part (light: the shared uL uniform, vec4s: its
 * length; hasAlbedo: the part has COLOR_0; baseColour: its base-colour texture, or null) for
 * `host` = { stages: { 'mesh.vert': text, ...,
 * fragment: text }, material(parameters) → a THREE material, uniforms: extra uniforms }.
 */
export function transferMaterial(t, light, vec4s, hasAlbedo, host, baseColour = null) {
  const d = drawOf(t);
  const defines = Object.assign({ PRT_LIGHT_VEC4S: vec4s, PRT_GLOSSY_COEFFS: kGlossyCoeffs }, d.defines || {});
  if (hasAlbedo) defines.PRT_HAS_ALBEDO = 1;
  const uniforms = Object.assign(d.uniforms(light), host.uniforms || {});
  if (baseColour) {
    // prt_fragment.glsl multiplies it into the diffuse part, unless the material's kd replaces
    // it (render::pixelTexture; setTransferUniforms).
    defines.PRT_BASE_COLOUR = 1;
    Object.assign(uniforms, { uBaseColour: { value: baseColour }, uBaseColourOn: { value: true } });
  }
  return host.material({ vertexShader: host.stages[d.stage], fragmentShader: host.stages.fragment, defines,
                         uniforms, hasAlbedo });
}

/** A data texture of RGBA32F texels, read with texelFetch. */
export function dataTexture(x) {
  const tex = new THREE.DataTexture(x.data, x.width, x.height, THREE.RGBAFormat, THREE.FloatType);
  tex.minFilter = tex.magFilter = THREE.NearestFilter;
  tex.generateMipmaps = false;
  tex.needsUpdate = true;
  return tex;
}

/**
 * The GPU side of a parsed bake for `host`: per part (in b.parts' order) one material and
 * texture per transfer, per transfer its per-frame table, the light uniform they share.
 * Returns { bake, light, tables, parts: [{ textures, materials }], points (the texels' points'
 * texture, or null) }.
 */
export function uploadTransfers(b, limits, host) {
  const vec4s = Math.ceil((b.maxBands * b.maxBands) / 4) * 4;
  const light = { value: new Float32Array(vec4s * 4) };
  const tables = {};
  for (const t of b.transfers) {
    const img = frameTable(t, limits, b.name);
    if (img) tables[t.key] = { image: img, texture: dataTexture(img) };
  }
  // One texture per image: a per-texel transfer's rows are one image every part shares.
  const made = new Map();
  const textureOf = (img) => made.get(img) || made.set(img, dataTexture(img)).get(img);
  const parts = b.parts.map((p) => {
    const textures = {}, materials = {};
    for (const t of b.transfers) {
      textures[t.key] = textureOf(p.texels[t.key]);
      materials[t.key] = transferMaterial(t, light, vec4s, p.hasAlbedo, host, p.baseColour);
    }
    return { textures, materials };
  });
  // Per-texel glossy matrices' points: one image for the bake.
  const points = b.texelPoints ? dataTexture(b.texelPoints) : null;
  return { bake: b, light, tables, parts, points };
}

/** Frees what uploadTransfers made, and the parts' base-colour textures it drew with (the
 *  loader's, whose materials the transfer materials replaced). */
export function disposeTransfers(gpu) {
  const textures = new Set();
  for (const p of gpu.bake.parts) if (p.baseColour) textures.add(p.baseColour);
  for (const p of gpu.parts) {
    for (const x of Object.values(p.materials)) x.dispose();
    for (const x of Object.values(p.textures)) textures.add(x);
  }
  for (const x of textures) x.dispose();
  for (const t of Object.values(gpu.tables)) t.texture.dispose();
  if (gpu.points) gpu.points.dispose();
}

/**
 * A frame's light for transfer t at b bands: L' = D(R) L for the first b bands of `coeffs`
 * (B² RGB, the light at the bake's bands), packed into the shared uniform as (r, g, b, 0), zero
 * past b²; then t's per-frame step into its table (CPCA: the cluster projections).
 */
export function setFrameLight(gpu, t, b, R, coeffs) {
  const rotated = rotateLight(b, R, coeffs);
  const L = gpu.light.value;
  L.fill(0);
  for (let i = 0; i < b * b; ++i) L[4 * i] = rotated[3 * i], L[4 * i + 1] = rotated[3 * i + 1], L[4 * i + 2] = rotated[3 * i + 2];
  const table = gpu.tables[t.key];
  if (table) {
    frameStep(t, b, rotated, table.image);
    table.texture.needsUpdate = true;
  }
}

/** Sets a frame's uniforms of t's material on part p of `gpu` (uploadTransfers'): f = { bands,
 *  eye } (eye: the camera's position in the part's frame). */
export function setTransferUniforms(gpu, p, t, f) {
  const part = gpu.parts[p], table = gpu.tables[t.key], u = part.materials[t.key].uniforms;
  if (u.uBaseColourOn) u.uBaseColourOn.value = !(t.material && t.material.kd);
  drawOf(t).set(u, t,
                    { bands: f.bands, eye: f.eye, rows: part.textures[t.key], table: table ? table.texture : null,
                      points: gpu.points });
}

/** What the status line says about how t is drawn. */
export function describeTransfer(t) {
  const lines = [];
  if (t.matrix) lines.push(`glossy ${t.material.material}, toward the eye`);
  if (t.perPixel) lines.push(`relit per pixel from a ${t.lightmap.width} x ${t.lightmap.height} lightmap`);
  if (t.compressed) {
    const c = t.compressed, dense = 16 * denseTexelsPerRow(t);
    lines.push(`relit compressed: CPCA ${c.clusters} x ${c.basisCount}, ${16 * c.texelsPerVertex} bytes/${t.perPixel ? 'texel' : 'vertex'} ` +
               `(dense ${dense}), ${16 * c.clusters * (c.basisCount + 1) * c.coeffs} bytes of cluster table per frame`);
  }
  return lines;
}
