// The domain of a bake's rows as the browser viewers read them (bake.js for SH transfer,
// haar_bake.js for Haar): every vertex, or every texel of one lightmap over the mesh's lightmap
// UVs (format 6 on; relit per pixel) — complete either way (prt merge joins the pieces) — and
// the lightmap UVs each part's lightmap stage reads (shaders/stages/lightmap.vert's
// prtLightmapUv). Probe grids have their own (probe_bake.js).
import { maxLightmapSide } from 'prt:constants';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/** { lightmap ({ width, height }, or null: the vertices), rowCount, uvName (GLTFLoader's name of
 *  the lightmap's TEXCOORD_n, or null) } of the bake's object `prt`; throws one line naming the
 *  file when the domain is not whole. */
export function rowDomain(prt, name) {
  if (!(prt.texelRange || prt.lightmap)) {
    const range = prt.vertexRange || {};
    if (range.first !== 0 || range.count !== prt.vertexCount)
      fail(name, `holds transfer for vertices ${range.first}..${range.first + range.count} of ${prt.vertexCount} only (merge the pieces with prt merge first)`);
    return { lightmap: null, rowCount: prt.vertexCount, uvName: null };
  }
  const lm = prt.lightmap || {}, range = prt.texelRange || {};
  if (!(Number.isInteger(lm.width) && Number.isInteger(lm.height) && lm.width >= 1 && lm.height >= 1 && lm.width <= maxLightmapSide && lm.height <= maxLightmapSide))
    fail(name, `holds per-texel transfer over a lightmap of ${lm.width} x ${lm.height} texels (1..${maxLightmapSide} a side expected)`);
  const rowCount = lm.width * lm.height;
  if (range.first !== 0 || range.count !== rowCount)
    fail(name, `holds transfer for texels ${range.first}..${range.first + range.count} of ${rowCount} only (merge the pieces with prt merge first)`);
  const set = prt.lightmapTexCoord;
  if (!(Number.isInteger(set) && set >= 0 && set <= 3))
    fail(name, 'holds per-texel transfer but names no lightmapTexCoord (0..3) it is over');
  return { lightmap: { width: lm.width, height: lm.height }, rowCount, uvName: set === 0 ? 'uv' : `uv${set}` };
}

/** Per texel: part `p`'s lightmap UVs (rowDomain's uvName) put where the lightmap stage reads
 *  them (prtLightmapUv); nothing per vertex. */
export function useLightmapUvs(p, domain, prt, name) {
  if (!domain.lightmap) return;
  const uv = p.geometry.getAttribute(domain.uvName);
  if (!uv || uv.itemSize !== 2 || uv.count !== p.vertices)
    fail(name, `part '${p.name}' has no lightmap UVs (TEXCOORD_${prt.lightmapTexCoord}), which its per-texel transfer is over`);
  p.geometry.setAttribute('prtLightmapUv', uv);
}
