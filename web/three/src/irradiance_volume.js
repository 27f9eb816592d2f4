// A relit probe grid as plain data an engine reads (docs/three.md, "Probe grids"): the JSON that
// `prt export PROBES.glb --format probe-grid --engine threejs` writes (io/probe_grid_export.hpp,
// docs/probes.md "Exports"), made here in the browser from the grid as it is relit now, plus
// every probe's position. Per probe, the nine RGB coefficients of the radiance arriving there
// (L2) in three.js's SphericalHarmonics3 convention — what LightProbe.sh holds, and what
// three.js's shGetIrradianceAt(n, sh) turns into the irradiance E(n) (ρ E(n)/π is then the
// diffuse exit radiance); three.js's basis is ours without the Condon–Shortley phase
// (coefficients 1, 3, 5, 7 change sign: light.js).
//
// three.js r187's LightProbeGridWebGL / LightProbeGrid over the same points: it puts probe
// (i, j, k) at position − size/2 + (i, j, k, + 0.5)·size/resolution, the centres of the cells of
// its box, as ours sit at the centres of the cells of the box baked (origin + (x·sx, y·sy, z·sz)):
// resolution = (nx, ny, nz), width/height/depth = (nx·sx, ny·sy, nz·sz), position the lattice's
// centre. (r184–r186 put the probes on the box's corners: size (n − 1)·s there.) Its texture is one RGBA float 3D atlas of
// nx × ny × 7 (nz + 2) texels (io::lightProbeGridAtlas, LightProbeGridWebGL.js): sub-volume t
// (0..6) holds floats 4t..4t+3 of each probe's 27 (SphericalHarmonics3.toArray() order, then a 0),
// probe layer z at slice t (nz + 2) + 1 + z, the first and last layers repeated in a padding
// slice at either end so trilinear filtering never reads the next sub-volume.

const kPadding = 1;  // io::kLightProbeGridPadding

/** A float as the shortest decimal that reads back to it (as prt export writes numbers). */
function shortest(x) {
  const f = Math.fround(x);
  for (let p = 1; p < 9; ++p) {
    const d = Number(f.toPrecision(p));
    if (Math.fround(d) === f) return d;
  }
  return Number(f.toPrecision(9));
}

/** Positions, origin, spacing of a grid { origin, spacing, count } (arrays of three). */
function lattice(grid) {
  const size = grid.count.map((n, a) => shortest(n * grid.spacing[a]));
  return { size, centre: grid.origin.map((o, a) => shortest(o + 0.5 * (grid.count[a] - 1) * grid.spacing[a])) };
}

/**
 * LightProbeGrid's constructor arguments and position for our grid: { position: [x, y, z],
 * width, height, depth, resolution: [nx, ny, nz] } — `new LightProbeGridWebGL(width, height,
 * depth, ...resolution)`, then `.position.set(...position)`.
 */
export function lightProbeGridParameters(grid) {
  const { size, centre } = lattice(grid);
  return { position: centre, width: size[0], height: size[1], depth: size[2], resolution: grid.count.slice() };
}

/**
 * LightProbeGrid's atlas of a grid whose probe p holds the 27 floats `sh` (three.js's basis)
 * from `sh[27 p]`: a Float32Array of nx × ny × 7 (nz + 2) RGBA texels, texel (x, y, slice) at
 * ((slice·ny + y)·nx + x)·4 — `new THREE.Data3DTexture(data, nx, ny, 7 * (nz + 2))`, RGBA,
 * FloatType, linear filtering.
 */
export function lightProbeGridAtlas(grid, sh) {
  const [nx, ny, nz] = grid.count, block = nz + 2 * kPadding;
  const data = new Float32Array(nx * ny * 7 * block * 4);
  for (let z = 0; z < nz; ++z)
    for (let y = 0; y < ny; ++y)
      for (let x = 0; x < nx; ++x) {
        const p = x + nx * (y + ny * z);
        for (let t = 0; t < 7; ++t) {
          const base = t * block;
          for (const slice of [base + kPadding + z, z === 0 ? base : -1, z === nz - 1 ? base + kPadding + nz : -1]) {
            if (slice < 0) continue;
            const texel = ((slice * ny + y) * nx + x) * 4;
            for (let i = 0; i < 4; ++i) data[texel + i] = 4 * t + i < 27 ? sh[27 * p + 4 * t + i] : 0;
          }
        }
      }
  return data;
}

/** Little-endian float32 bytes as base64. */
function base64Floats(x) {
  const bytes = new Uint8Array(x.length * 4), view = new DataView(bytes.buffer);
  for (let i = 0; i < x.length; ++i) view.setFloat32(4 * i, x[i], true);
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

/**
 * The JSON object of a relit grid (see the top): `grid` { origin, spacing, count }; `sh3(p,
 * out)` fills probe p's 27 floats in three.js's basis; `positionOf(p, out)` its position;
 * `about` = { source, light, rotateDegrees, generator }. Probe p = x + nx·(y + ny·z):
 * `probes[(p·9 + k)·3 + c]` is coefficient k, channel c; `positions[3p + a]` its position.
 */
export function irradianceVolumeJson(grid, sh3, positionOf, about) {
  const P = grid.count[0] * grid.count[1] * grid.count[2];
  const sh = new Float32Array(27 * P), positions = new Array(3 * P), at = [0, 0, 0];
  for (let p = 0; p < P; ++p) {
    sh3(p, sh.subarray(27 * p, 27 * p + 27));
    positionOf(p, at);
    for (let a = 0; a < 3; ++a) positions[3 * p + a] = shortest(at[a]);
  }
  const lightProbeGrid = lightProbeGridParameters(grid);
  lightProbeGrid.atlas = {
    size: [grid.count[0], grid.count[1], 7 * (grid.count[2] + 2 * kPadding)], padding: kPadding,
    format: 'RGBA, float32 little-endian, texel (x, y, slice) at ((slice ny + y) nx + x) 4',
    data: base64Floats(lightProbeGridAtlas(grid, sh)),
  };
  return {
    asset: { generator: about.generator, format: 'prtkit probe grid', version: 1 },
    source: about.source, light: about.light, rotateDegrees: about.rotateDegrees, exposureStops: 0,
    engine: 'threejs',
    grid: { origin: grid.origin.map(shortest), spacing: grid.spacing.map(shortest), count: grid.count.slice(),
            order: 'x + nx (y + ny z)' },
    lightProbeGrid,
    coefficients: { count: 9, bands: 3, layout: 'probe-major, then coefficient, then r g b' },
    probes: Array.from(sh, shortest),
    positions,
  };
}
