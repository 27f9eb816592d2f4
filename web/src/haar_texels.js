// A per-texel Haar bake drawn per pixel in the page and prtkit-three, as prt view draws one
// (relight::packRadianceLightmap; docs/haar.md "Per texel"): each texel relit on the CPU at its
// normal — from the texel points prt web ships beside its bake (render::texelRelight: a gutter
// texel at the neighbour whose row it copies, an occluded-part row adding the unshadowed light at
// its normal) — with the recipe's kd, else white, into one image of W·H texels (r, g, b, 0). The
// image is drawn through the SH lightmaps' per-pixel stage (draw.js, shaders/prt_lightmap.glsl)
// as a one-band RGB transfer against a unit light: its T·L' is the radiance itself, blended over
// prt render's four bilinear taps and times the albedo per pixel (COLOR_0, unless a kd, which
// the radiance then holds) — what prt render draws.
import { dataTexture, setRowUniforms, transferMaterial } from './draw.js';
import { relightHaar } from './haar_relight.js';
import { textureShape } from './texels.js';

/** The normals of a per-texel Haar bake's rows in render::packTexelPoints' twelve floats a
 *  texel (position, normal, albedo, each padded to four), checked: one row a texel, finite. */
export function texelNormalsOf(points, rows, name) {
  if (!(points instanceof Float32Array) || points.length !== rows * 12)
    throw new Error(`${name}: its texel points hold ${points && points.length} floats, ${rows * 12} expected (twelve a texel of the lightmap)`);
  const normals = new Float32Array(3 * rows);
  for (let r = 0; r < rows; ++r)
    for (let c = 0; c < 3; ++c) {
      const v = points[12 * r + 4 + c];
      if (!Number.isFinite(v)) throw new Error(`${name}: its texel points: value ${12 * r + 4 + c} is not finite`);
      normals[3 * r + c] = v;
    }
  return normals;
}

/**
 * The drawing of a per-texel Haar bake `b` (haar_bake.js's readHaarBake: b.lightmap, b.texelNormals)
 * for `host` (draw.js's): { material(p, t) (part p's material for transfer t), relight(t,
 * light) (the texels relit and uploaded; returns the radiance), dispose() }.
 */
export function haarTexelDrawing(b, limits, host) {
  const lm = b.lightmap, rows = lm.width * lm.height;
  const shape = { perPixel: true, path: 'DenseVector', channels: 3, texelsPerRow: 1, lightmap: lm };
  // The unit light the stage's one band meets (std140 vec4s, padded to four).
  const light = { value: new Float32Array(16) };
  light.value.set([1, 1, 1, 0]);
  const image = textureShape(rows, limits, b.name, 'the relit lightmap');
  const texture = dataTexture(image);
  const radiance = new Float32Array(3 * rows);
  const made = new Map();
  return {
    material(p, t) {
      // A kd replaces the albedo per pixel (render::texelAlbedo): the radiance holds it.
      const withAlbedo = b.parts[p].hasAlbedo && !t.kd, key = `${p} ${withAlbedo}`;
      if (!made.has(key)) {
        const m = transferMaterial(shape, light, 4, withAlbedo, host);
        setRowUniforms(m, shape, { bands: 1, rows: texture });
        made.set(key, m);
      }
      return made.get(key);
    },
    relight(t, haarLight) {
      relightHaar(t, haarLight, b.texelNormals, t.kd || null, radiance, 0, rows);
      for (let r = 0; r < rows; ++r)
        image.data[4 * r] = radiance[3 * r], image.data[4 * r + 1] = radiance[3 * r + 1], image.data[4 * r + 2] = radiance[3 * r + 2];
      texture.needsUpdate = true;
      return radiance;
    },
    dispose() {
      for (const m of made.values()) m.dispose();
      texture.dispose();
    },
  };
}
