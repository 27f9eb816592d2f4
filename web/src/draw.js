// The GPU side of a transfer, by path (transfer.js decides the path once): the stage that
// draws it (shaders/stages/), its uniforms, what each frame sets — as the desktop viewer's
// renderer does per path — and the per-frame light and cluster table every material of a bake
// shares. The stages come flattened for a host (cmake/Shaders.cmake): the page's (webgl2,
// RawShaderMaterial into its HDR target, page_host.js) or the three.js module's (three,
// ShaderMaterial in anyone's scene, web/three). Nothing here touches a scene.
// A per-vertex matrix transfer drawn through an irradiance encoding (dense matrices always,
// CPCA ones when an encoding is chosen: encoded_diffuse.js) is drawn from radiance made on the
// CPU, by the radiance stage (shaders/stages/radiance.vert), one material a part.
import * as THREE from 'three';
import { bands as kBands } from 'prt:constants';
import { denseTexelsPerRow, frameStep, frameTable } from './transfer.js';
import { rotateLight } from './sh.js';
import { incidentRows, lobeLeftOut, shadeEncoded, shownEncoding } from './encoded_diffuse.js';
import { packed } from './radiance_mesh.js';

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

/** Sets the uniforms of `material` (transferMaterial's for t) that draw t from `f` = { bands,
 *  rows (the rows' texture), table, eye, points }: what setTransferUniforms sets for a bake's
 *  own transfer, for a drawing made outside uploadTransfers (haar_texels.js). */
export function setRowUniforms(material, t, f) {
  drawOf(t).set(material.uniforms, t, f);
}

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
// Radiance made on the CPU (an irradiance encoding's kd ⊙ Ê(n)/π per vertex): passed through.
const kRadianceDraw = { stage: 'radiance.vert', uniforms: () => ({}), set() {} };

/**
 * The material that draws transfer t on a part (light: the shared uL uniform, vec4s: its
 * length; hasAlbedo: the part has COLOR_0; baseColour: its base-colour texture, or null) for
 * `host` = { stages: { 'mesh.vert': text, ...,
 * fragment: text }, material(parameters) → a THREE material, uniforms: extra uniforms }.
 */
export function transferMaterial(t, light, vec4s, hasAlbedo, host, baseColour = null) {
  return stageMaterial(drawOf(t), light, vec4s, hasAlbedo, host, baseColour);
}

function stageMaterial(d, light, vec4s, hasAlbedo, host, baseColour) {
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

/** Whether a bake's transfer can be drawn through an encoding (a per-vertex matrix). */
const encodable = (t) => t.matrix && !t.perPixel;

/**
 * A part's radiance drawing (for a bake with per-vertex matrices): its material (the radiance
 * stage; the albedo is in the radiance, the base-colour texture multiplies per pixel), the
 * per-vertex `radiance` attribute it reads (and a zero `lobe`, the texture's unmultiplied part),
 * and the packed normals and albedo the radiance is made from.
 */
function radianceDrawing(p, light, vec4s, host) {
  const g = p.geometry, V = g.getAttribute('position').count;
  const radiance = new THREE.Float32BufferAttribute(new Float32Array(3 * V), 3);
  g.setAttribute('radiance', radiance);
  if (p.baseColour) g.setAttribute('lobe', new THREE.Float32BufferAttribute(new Float32Array(3 * V), 3));
  const colour = g.getAttribute('color');
  return { material: stageMaterial(kRadianceDraw, light, vec4s, false, host, p.baseColour), radiance,
           normals: packed(g.getAttribute('normal')), albedo: colour ? packed(colour) : null };
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
  const encoded = b.transfers.some(encodable);
  const parts = b.parts.map((p) => {
    const textures = {}, materials = {};
    const radiance = encoded ? radianceDrawing(p, light, vec4s, host) : null;
    for (const t of b.transfers) {
      // (CpuRadiance has no rows on the GPU, and is drawn by the part's radiance material only.)
      textures[t.key] = p.texels[t.key] ? textureOf(p.texels[t.key]) : null;
      materials[t.key] = t.path === 'CpuRadiance' ? radiance.material
        : transferMaterial(t, light, vec4s, p.hasAlbedo, host, p.baseColour);
    }
    return { textures, materials, radiance };
  });
  // Per-texel glossy matrices' points: one image for the bake.
  const points = b.texelPoints ? dataTexture(b.texelPoints) : null;
  return { bake: b, light, tables, parts, points, rotated: null, encodedFor: null };
}

/** Frees what uploadTransfers made, and the parts' base-colour textures it drew with (the
 *  loader's, whose materials the transfer materials replaced). */
export function disposeTransfers(gpu) {
  const textures = new Set();
  for (const p of gpu.bake.parts) if (p.baseColour) textures.add(p.baseColour);
  for (const p of gpu.parts) {
    for (const x of Object.values(p.materials)) x.dispose();
    if (p.radiance) p.radiance.material.dispose();
    for (const x of Object.values(p.textures)) if (x) textures.add(x);
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
  gpu.rotated = rotated;
}

/**
 * The material transfer t wears on part p of `gpu` when drawn through `encoding` ('none' or a
 * name): the part's radiance material if t is drawn through one (encoded_diffuse.js
 * shownEncoding), else t's own.
 */
export function transferMaterialOf(gpu, p, t, encoding) {
  return shownEncoding(t, encoding) ? gpu.parts[p].radiance.material : gpu.parts[p].materials[t.key];
}

/**
 * After setFrameLight for transfer t at b bands: if t is drawn through `encoding` ('none' or a
 * name, shownEncoding), every part's radiance kd ⊙ Ê(n)/π per vertex (encoded_diffuse.js) — made
 * again only when the transfer, the bands, the encoding or the rotated light changed. Returns
 * whether it made it.
 */
export function setEncodedRadiance(gpu, t, b, encoding) {
  const shown = shownEncoding(t, encoding);
  if (!shown) return false;
  const last = gpu.encodedFor, light = gpu.rotated;
  if (last && last.t === t && last.b === b && last.encoding === shown && last.light.length === light.length &&
      last.light.every((x, i) => x === light[i])) return false;
  const table = gpu.tables[t.key];
  const incident = incidentRows(t, b, light, table ? table.image.data : null);
  const kd = t.material && t.material.kd;
  gpu.bake.parts.forEach((p, i) => {
    const r = gpu.parts[i].radiance;
    shadeEncoded(incident, b, shown, p.first, r.normals, r.albedo, kd, r.radiance.array);
    r.radiance.needsUpdate = true;
  });
  gpu.encodedFor = { t, b, encoding: shown, light: Float32Array.from(light) };
  return true;
}

/** Sets a frame's uniforms of t's material on part p of `gpu` (uploadTransfers'): f = { bands,
 *  eye, encoding } (eye: the camera's position in the part's frame; encoding: 'none' or the
 *  name t is drawn through, transferMaterialOf). */
export function setTransferUniforms(gpu, p, t, f) {
  const part = gpu.parts[p], table = gpu.tables[t.key];
  const encoded = !!shownEncoding(t, f.encoding);
  const u = (encoded ? part.radiance.material : part.materials[t.key]).uniforms;
  if (u.uBaseColourOn) u.uBaseColourOn.value = !(t.material && t.material.kd);
  (encoded ? kRadianceDraw : drawOf(t)).set(u, t,
                    { bands: f.bands, eye: f.eye, rows: part.textures[t.key], table: table ? table.texture : null,
                      points: gpu.points });
}

/** What the status line says about how t is drawn (through `encoding`: 'none' or a name). */
export function describeTransfer(t, encoding = 'none') {
  const lines = [];
  const shown = shownEncoding(t, encoding);
  if (shown) {
    lines.push(`diffuse through ${shown} irradiance: kd ⊙ Ê(n)/π per vertex, made on the CPU` +
               (encoding === 'none' ? ' (dense matrices: l2 unless an encoding is chosen)' : ''));
    if (lobeLeftOut(t)) lines.push(`the ${t.material.material} lobe is left out (an encoding holds irradiance)`);
    return lines;
  }
  if (t.matrix) lines.push(`glossy ${t.material.material}, toward the eye`);
  if (t.perPixel) lines.push(`relit per pixel from a ${t.lightmap.width} x ${t.lightmap.height} lightmap`);
  if (t.compressed) {
    const c = t.compressed, dense = 16 * denseTexelsPerRow(t);
    lines.push(`relit compressed: CPCA ${c.clusters} x ${c.basisCount}, ${16 * c.texelsPerVertex} bytes/${t.perPixel ? 'texel' : 'vertex'} ` +
               `(dense ${dense}), ${16 * c.clusters * (c.basisCount + 1) * c.coeffs} bytes of cluster table per frame`);
  }
  return lines;
}
