// node check.mjs GOLDEN.json GENDIR: feeds the inputs prt_web_golden wrote (write_golden.cpp) to
// the page's own functions (web/src, with the generated 'prt:' imports resolved into GENDIR by
// imports.mjs) and compares with the library's outputs. Prints one line per group; on a
// mismatch prints what differs (case, index, page and library values) and exits 1.
import fs from 'node:fs';
import path from 'node:path';
import { register } from 'node:module';

const [goldenPath, gen] = process.argv.slice(2);
if (!goldenPath || !gen) {
  console.error('usage: node check.mjs GOLDEN.json GENDIR');
  process.exit(2);
}
register('./imports.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const src = new URL('../../../web/src/', import.meta.url);
const { rotationEulerXYZ, rotateLight, axisAngle, evalSh } = await import(new URL('sh.js', src));
const { projectClusters, packWeights, clusterTableImage } = await import(new URL('compressed.js', src));
const { parseBake } = await import(new URL('bake.js', src));
const { frameView } = await import(new URL('camera.js', src));
const { parseLightJson, lightForTransfer } = await import(new URL('lights.js', src));
const { bandLimitMessage } = await import(new URL('messages.js', src));
const { encode, evaluate, encodingNames } = await import(new URL('irradiance_encoding.js', src));
const { incidentRows, shadeEncoded } = await import(new URL('encoded_diffuse.js', src));
const { irradianceEncodings } = await import('prt:constants');

const golden = JSON.parse(fs.readFileSync(goldenPath, 'utf8'));
const dir = path.dirname(goldenPath);
const failures = [];
const fail = (msg) => failures.push(msg);

/** Compares got[i] with want[i] to |d| ≤ tol·max(1, |want|); returns the largest |d|. A length
 *  mismatch or the first out-of-tolerance value is a failure naming `what`. tol 0: exact as
 *  float32 (packing copies values). */
function compare(what, got, want, tol) {
  if (got.length < want.length) {
    fail(`${what}: the page gives ${got.length} values, the library ${want.length}`);
    return Infinity;
  }
  let worst = 0, reported = false;
  for (let i = 0; i < want.length; ++i) {
    const w = tol === 0 ? Math.fround(want[i]) : want[i], g = got[i];
    const d = Math.abs(g - w);
    if (!(d <= tol * Math.max(1, Math.abs(w)))) {
      if (!reported) fail(`${what}: value ${i}: page ${g}, library ${w} (difference ${d}, tolerance ${tol === 0 ? 'exact' : tol})`);
      reported = true;
      worst = Math.max(worst, Number.isFinite(d) ? d : Infinity);
    } else worst = Math.max(worst, d);
  }
  return worst;
}
function expect(cond, what) {
  if (!cond) fail(what);
}
const largest = (xs) => xs.reduce((a, b) => Math.max(a, b), 0);
const maxAbs = (xs) => largest(Array.from(xs, Math.abs));

// ---- SH rotation (sh.js) against sh::Rotation ------------------------------------------------
{
  const d = golden.rotation.map((c) => {
    const out = rotateLight(c.bands, rotationEulerXYZ(...c.euler), Float64Array.from(c.light),
                            new Float64Array(c.bands * c.bands * 3));
    const what = `rotation, ${c.bands} bands, Euler ${c.euler.map((x) => x.toFixed(2)).join(',')}`;
    // Not vacuous: a turn about a tilted axis moves a light of 2+ bands.
    if (c.bands > 1 && c.euler.some((x) => Math.abs(x) > 1))
      expect(largest(c.rotated.map((v, i) => Math.abs(v - c.light[i]))) > 0.01, `${what}: the library's rotation left the light in place (bad golden case)`);
    return compare(what, out, c.rotated, 1e-5);
  });
  const a = golden.axisAngle.map((c, k) => compare(`axisAngle case ${k}`, axisAngle(c.axis, c.angle).flat(), c.matrix.flat(), 1e-12));
  console.log(`rotation: ${d.length} lights at 1..9 bands, largest difference ${largest(d).toExponential(2)} (tolerance 1e-5); ` +
              `axis-angle: ${a.length} matrices, ${largest(a).toExponential(2)}`);
}

// ---- SH evaluation (sh.js, the SH background) against sh::eval ---------------------------------
{
  const d = golden.evalSh.map((c) => compare(`evalSh, ${c.bands} bands at (${c.dir.map((x) => x.toFixed(3))})`,
                                             evalSh(c.bands, c.dir[0], c.dir[1], c.dir[2]), c.values, 1e-10));
  console.log(`evalSh: ${d.length} directions, largest difference ${largest(d).toExponential(2)} (tolerance 1e-10)`);
}

// ---- cluster projection and packing (compressed.js) against relight::projectClusters -----------
const limits = { maxTextureSize: 16384, maxBands: 15, maxFragmentBands: 14 };
/** The arrays as bake.js reads them (readCompressed's result) from a golden transfer. */
function compressedOf(c) {
  const n = c.bands * c.bands, matrix = c.layout === 'matrix';
  return { clusters: c.clusters, basisCount: c.basisCount, stride: (matrix ? n * n : n) * c.channels,
           texelsPerVertex: Math.ceil((c.basisCount + 1) / 4), coeffs: matrix ? n : 1, bands: c.bands,
           cluster: Uint32Array.from(c.cluster), weights: Float32Array.from(c.weights),
           means: Float32Array.from(c.means), basis: Float32Array.from(c.basis) };
}
{
  const d = [];
  for (const c of golden.clusters) {
    const name = `${c.layout} ${c.bands} bands ${c.channels === 3 ? 'RGB' : 'scalar'}, K ${c.clusters} N ${c.basisCount}`;
    const x = compressedOf(c);
    expect(x.texelsPerVertex === c.texelsPerRow, `${name}: ${x.texelsPerVertex} texels per vertex, the library ${c.texelsPerRow}`);
    compare(`${name}: per-vertex texels`, packWeights(x, 0, c.rows, limits, 'golden', 'test').data, c.packedRows, 0);
    for (const f of c.frames) {
      const table = clusterTableImage(x, limits, 'golden', 'test');
      projectClusters(x, f.bands, c.channels, Float32Array.from(f.light), table.data);
      expect(maxAbs(f.table) > 0.01, `${name}: the library's table at ${f.bands} bands is all zero (bad golden case)`);
      d.push(compare(`${name}: cluster table at ${f.bands} bands`, table.data, f.table, 1e-5));
    }
  }
  console.log(`cluster projection: ${d.length} tables (${golden.clusters.length} transfers, b = B and B − 1), ` +
              `largest difference ${largest(d).toExponential(2)} (tolerance 1e-5); per-vertex texels exact`);
}

// ---- decoding a bake (bake.js): pick order, texels, framing ------------------------------------
{
  const g = golden.bake;
  const bytes = fs.readFileSync(path.join(dir, g.file));
  const b = await parseBake(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), g.file, limits);
  const got = b.transfers.map((t) => `${t.mode} ${t.layout}`), want = g.transfers.map((t) => `${t.mode} ${t.layout}`);
  expect(got.join(', ') === want.join(', '), `bake: transfers in the order [${got.join(', ')}], the library's (transferPreference) [${want.join(', ')}]`);
  expect(b.vertices === g.vertices, `bake: ${b.vertices} vertices, the library ${g.vertices}`);
  const parts = b.parts.map((p) => `${p.name}@${p.first}+${p.vertices}`), wantParts = g.parts.map((p) => `${p.name}@${p.first}+${p.vertices}`);
  expect(parts.join(' ') === wantParts.join(' '), `bake: parts ${parts.join(' ')}, the library's ${wantParts.join(' ')}`);
  let values = 0;
  for (const w of g.transfers) {
    const t = b.transfers.find((u) => u.mode === w.mode && u.layout === w.layout);
    if (!t) continue;
    const what = `bake: the ${w.mode} ${w.layout} transfer`;
    expect(!!t.compressed === w.compressed, `${what}: compressed ${!!t.compressed}, the library ${w.compressed}`);
    expect(t.texelsPerRow === w.texelsPerRow, `${what}: ${t.texelsPerRow} texels per vertex, the library's packShaderRows ${w.texelsPerRow}`);
    const T4 = 4 * w.texelsPerRow;
    for (const p of b.parts) {
      compare(`${what}, part ${p.name}: packed texels`, p.texels[t.key].data.subarray(0, p.vertices * T4),
              w.packedRows.slice(p.first * T4, (p.first + p.vertices) * T4), 0);
      values += p.vertices * T4;
    }
  }
  const f = g.framing;
  const dc = compare('bake: framing centre (render::meshFraming)', b.centre.toArray(), f.centre, 1e-6);
  const dr = compare('bake: framing radius (render::meshFraming)', [b.radius], [f.radius], 1e-6);
  const v = frameView({ ...f, centre: b.centre.toArray(), radius: b.radius }, g.width, g.height);
  const dv = compare(`bake: camera at ${g.width}x${g.height} (render::frameCamera)`, [...v.eye, ...v.target, ...v.up, v.fov],
                     [...g.camera.eye, ...g.camera.target, ...g.camera.up, g.camera.fov], 1e-5);
  console.log(`bake: ${b.transfers.length} transfers in the library's order, ${values} packed texel values exact over ` +
              `${b.parts.length} parts, framing within ${largest([dc, dr]).toExponential(2)}, camera ${dv.toExponential(2)}`);
}

// ---- a per-texel bake (bake.js, transfer.js): the lightmap's rows packed once, as the library --
{
  const g = golden.texelBake;
  const bytes = fs.readFileSync(path.join(dir, g.file));
  const b = await parseBake(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), g.file, limits);
  expect(b.lightmap && b.lightmap.width === g.width && b.lightmap.height === g.height,
         `texel bake: lightmap ${JSON.stringify(b.lightmap)}, the library's ${g.width} x ${g.height}`);
  let values = 0;
  for (const w of g.transfers) {
    const t = b.transfers.find((u) => u.mode === w.mode);
    expect(!!t, `texel bake: no ${w.mode} transfer read`);
    if (!t) continue;
    const what = `texel bake: the ${w.mode} transfer`;
    expect(t.perPixel === w.perPixel && !!t.compressed === w.compressed, `${what}: perPixel ${t.perPixel}, compressed ${!!t.compressed}`);
    expect(t.texelsPerRow === w.texelsPerRow, `${what}: ${t.texelsPerRow} texels per row, the library's packShaderRows ${w.texelsPerRow}`);
    for (const p of b.parts) {
      expect(p.texels[t.key] === b.parts[0].texels[t.key], `${what}: part ${p.name} has rows of its own (one lightmap for all)`);
      expect(!!p.geometry.getAttribute('prtLightmapUv'), `${what}: part ${p.name} has no prtLightmapUv`);
    }
    compare(`${what}: packed texel rows`, b.parts[0].texels[t.key].data.subarray(0, w.packedRows.length), w.packedRows, 0);
    values += w.packedRows.length;
  }
  console.log(`texel bake: ${g.transfers.length} per-texel transfers, ${values} packed values exact, one image for ${b.parts.length} parts`);
}

// ---- light files (lights.js) against io::loadLighting + io::padded -----------------------------
{
  for (const c of golden.lights) {
    const l = lightForTransfer(c.path, parseLightJson(fs.readFileSync(c.path, 'utf8'), c.path), c.transferBands);
    const what = `light ${c.file} for ${c.transferBands} bands`;
    expect(JSON.stringify(l.warnings) === JSON.stringify(c.warnings),
           `${what}: the page warns ${JSON.stringify(l.warnings)}, the library ${JSON.stringify(c.warnings)}`);
    compare(`${what}: coefficients`, l.coeffs, c.coefficients, 0);
  }
  for (const m of golden.messages) {
    const got = bandLimitMessage(m.what, m.bands, m.who, m.max);
    expect(got === m.message, `bandLimitMessage: the page says "${got}", the library "${m.message}"`);
  }
  console.log(`lights: ${golden.lights.length} files (fewer, one fewer, more, as many bands), warnings and padding as the library; ` +
              `${golden.messages.length} band-limit messages`);
}

// ---- irradiance encodings (irradiance_encoding.js) against sh::encodeIrradiance, sh::evaluate ----
{
  const g = golden.encodings, normals = g.normals;
  // The names: the library's list, in its order (kIrradianceEncodings, generated).
  const libraryNames = g.lights[0].encoded.map((e) => e.encoding);
  expect(encodingNames.join(' ') === libraryNames.join(' '),
         `encodings: the page lists ${encodingNames.join(', ')}, the library ${libraryNames.join(', ')}`);
  expect(irradianceEncodings.length === 9, `encodings: ${irradianceEncodings.length} generated, 9 expected`);
  const d = [], spread = {};
  for (const c of g.lights) {
    for (const w of c.encoded) {
      const what = `encoding ${w.encoding} of the light '${c.light}' (${c.bands} bands)`;
      const x = encode(Float32Array.from(c.coefficients), c.bands, w.encoding);
      d.push(compare(`${what}: irradiance SH`, x.sh, w.sh, 1e-5));
      d.push(compare(`${what}: zonal coefficients`, x.zonal, w.zonal, 1e-5));
      // The axis up to its sign (a and −a are the same zonal harmonic), where it matters.
      if (w.zonal.some((z) => Math.abs(z) > 1e-6)) {
        const s = Math.sign(x.axis[0] * w.axis[0] + x.axis[1] * w.axis[1] + x.axis[2] * w.axis[2]) || 1;
        d.push(compare(`${what}: axis`, x.axis.map((a) => s * a), w.axis, 1e-5));
      }
      const values = normals.flatMap((n) => evaluate(x, n[0], n[1], n[2]));
      d.push(compare(`${what}: evaluated at ${normals.length} normals`, values, w.values, 1e-5));
      (spread[c.light] = spread[c.light] || []).push(w.values);
    }
  }
  // Not vacuous: on the sun, the encodings differ from one another.
  const sun = spread.sun, l1 = sun[encodingNames.indexOf('l1')];
  const apart = (a, b) => largest(sun[encodingNames.indexOf(a)].map((v, i) => Math.abs(v - sun[encodingNames.indexOf(b)][i])));
  for (const name of ['l1-windowed', 'l1-geomerics', 'zh3-hallucinated', 'zh3', 'zh3-shared', 'zh3-optimal', 'l2'])
    expect(apart(name, 'l1') > 1e-3, `encodings: ${name} evaluates as l1 does on the sun (bad golden case)`);
  expect(apart('l2-deringed', 'l2') > 1e-3, 'encodings: the sun\'s l2 needs no de-ringing (bad golden case)');
  expect(apart('zh3-optimal', 'zh3') > 1e-6, 'encodings: on the sun the best zonal axis is the luminance\'s (bad golden case)');
  expect(apart('zh3-shared', 'zh3') > 1e-6, 'encodings: on the sun one shared zonal is zh3\'s three (bad golden case)');
  expect(apart('zh3-shared', 'zh3-optimal') > 1e-6, 'encodings: on the sun one shared zonal is zh3-optimal\'s three (bad golden case)');
  console.log(`encodings: ${encodingNames.length} encodings of ${g.lights.length} lights (1..4 bands, one ringing, one ` +
              `with a negative mean) at ${normals.length} normals, largest difference ${largest(d).toExponential(2)} (tolerance 1e-5)`);
}

// ---- a matrix transfer drawn through an encoding (encoded_diffuse.js) against relight::encodedDiffuse
{
  const d = [];
  for (const c of golden.encodedDiffuse) {
    const b = c.shown, what = `encodedDiffuse, ${c.compressed ? 'CPCA' : 'dense'} ${c.bands}-band ` +
      `${c.channels === 3 ? 'RGB' : 'scalar'} matrices shown at ${b} bands, ${c.encoding}${c.kd ? ', kd' : ''}`;
    const light = Float32Array.from(c.light);
    let t, table = null;
    if (c.compressed) {
      const x = compressedOf(c);
      t = { matrix: true, bands: c.bands, channels: c.channels, compressed: x };
      const img = clusterTableImage(x, limits, 'golden', 'test');
      projectClusters(x, b, c.channels, light, img.data);
      table = img.data;
    } else {
      t = { matrix: true, bands: c.bands, channels: c.channels, compressed: null, matrices: Float32Array.from(c.matrices) };
    }
    const out = new Float32Array(3 * c.rows);
    shadeEncoded(incidentRows(t, b, light, table), b, c.encoding, 0, Float32Array.from(c.normals),
                 Float32Array.from(c.albedo), c.kd, out);
    expect(maxAbs(c.radiance) > 0.01, `${what}: the library's radiance is all zero (bad golden case)`);
    d.push(compare(what, out, c.radiance, 1e-5));
  }
  console.log(`encodedDiffuse: ${d.length} matrix transfers (dense and CPCA, RGB and scalar, all and fewer bands, ` +
              `albedo and kd), largest difference ${largest(d).toExponential(2)} (tolerance 1e-5)`);
}

if (failures.length) {
  console.error(`\n${failures.length} mismatch(es) between the page's JS and the library:`);
  for (const f of failures.slice(0, 30)) console.error('  ' + f);
  process.exit(1);
}
console.log('the page computes what the library computes');
