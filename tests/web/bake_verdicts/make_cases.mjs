// node make_cases.mjs OUTDIR VERTEX.glb TEXEL.glb CPCA.glb TEXEL_CPCA.glb PROBES.glb PROBES_CPCA.glb
// HAAR.glb HAAR_TEXEL.glb HAAR_128.glb HAAR_IR.glb (a 2 x 2 x 2 probe grid, dense and
// CPCA-compressed; Haar transfer per vertex over a 4² cube, per texel, per vertex over a 128²
// cube, which the browser viewers do not take, and inter-reflected): writes the malformed
// (and a few valid) bakes of the verdict corpus into OUTDIR, each a mutation of a bake prt wrote
// (run.sh), named accept_* or reject_* after what the library is meant to answer (verdicts.mjs
// checks that prt does, so a mutation that stops breaking the file fails the test). The GLB is
// rewritten with its JSON and BIN chunks re-laid, so only the mutation differs.
import fs from 'node:fs';
import path from 'node:path';

const [out, vertexFile, texelFile, cpcaFile, texelCpcaFile, probesFile, probesCpcaFile, haarFile, haarTexelFile,
       haar128File, haarIrFile] = process.argv.slice(2);
if (!haarIrFile) {
  console.error('usage: node make_cases.mjs OUTDIR VERTEX.glb TEXEL.glb CPCA.glb TEXEL_CPCA.glb PROBES.glb PROBES_CPCA.glb HAAR.glb HAAR_TEXEL.glb HAAR_128.glb HAAR_IR.glb');
  process.exit(2);
}
const EXT = 'PRTKIT_radiance_transfer';

function readGlb(file) {
  const b = fs.readFileSync(file);
  const jsonLength = b.readUInt32LE(12);
  const json = JSON.parse(b.subarray(20, 20 + jsonLength).toString('utf8'));
  const binAt = 20 + jsonLength, binLength = b.readUInt32LE(binAt);
  return { json, bin: Buffer.from(b.subarray(binAt + 8, binAt + 8 + binLength)) };
}
function writeGlb({ json, bin }, text = JSON.stringify(json)) {
  let j = Buffer.from(text, 'utf8');
  if (j.length % 4) j = Buffer.concat([j, Buffer.alloc(4 - (j.length % 4), 0x20)]);
  const head = Buffer.alloc(20), binHead = Buffer.alloc(8);
  head.writeUInt32LE(0x46546c67, 0), head.writeUInt32LE(2, 4);
  head.writeUInt32LE(20 + j.length + 8 + bin.length, 8);
  head.writeUInt32LE(j.length, 12), head.writeUInt32LE(0x4e4f534a, 16);
  binHead.writeUInt32LE(bin.length, 0), binHead.writeUInt32LE(0x004e4942, 4);
  return Buffer.concat([head, j, binHead, bin]);
}
const bases = { v: readGlb(vertexFile), t: readGlb(texelFile), c: readGlb(cpcaFile), tc: readGlb(texelCpcaFile),
                p: readGlb(probesFile), pc: readGlb(probesCpcaFile), h: readGlb(haarFile), ht: readGlb(haarTexelFile),
                h128: readGlb(haar128File), hi: readGlb(haarIrFile) };
const copy = (g) => ({ json: structuredClone(g.json), bin: Buffer.from(g.bin) });

// Helpers on a copy: the bake object, accessors by index or name, element addresses.
const prt = (g) => g.json.extensions[EXT];
const prim = (g, m = 0) => g.json.meshes[m].primitives[0];
const accIndex = (g, name) => g.json.accessors.findIndex((a) => a.name && a.name.startsWith(name));
const cpca = (g) => prt(g).transfers.find((t) => t.compressed);
const transferAcc = (g, t = 0, k = 0) => prt(g).transfers[t].accessors[k];
function at(g, index, i, c = 0) {
  const a = g.json.accessors[index], v = g.json.bufferViews[a.bufferView];
  const size = { 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 }[a.componentType];
  const comps = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 }[a.type];
  const stride = v.byteStride || size * comps;
  return (v.byteOffset || 0) + (a.byteOffset || 0) + i * stride + c * size;
}
const setFloat = (g, index, i, c, x) => g.bin.writeFloatLE(x, at(g, index, i, c));

const cases = {
  // Valid files, and edges the library accepts.
  accept_vertex: ['v', () => {}],
  accept_texel: ['t', () => {}],
  accept_cpca: ['c', () => {}],
  accept_texel_cpca: ['tc', () => {}],
  accept_lightmap_uv_at_one: ['t', (g) => setFloat(g, prim(g).attributes.TEXCOORD_0, 0, 0, 1.0000005)],
  // The mesh.
  reject_position_nan: ['v', (g) => setFloat(g, prim(g).attributes.POSITION, 1, 1, NaN)],
  reject_position_nan_texel: ['t', (g) => setFloat(g, prim(g, 2).attributes.POSITION, 0, 0, NaN)],
  reject_position_infinite: ['v', (g) => setFloat(g, prim(g, 1).attributes.POSITION, 0, 2, -Infinity)],
  reject_normal_nan: ['v', (g) => setFloat(g, prim(g).attributes.NORMAL, 0, 0, NaN)],
  reject_colour_nan: ['v', (g) => setFloat(g, prim(g).attributes.COLOR_0, 2, 1, NaN)],
  reject_coordinate_1e12: ['v', (g) => setFloat(g, prim(g).attributes.POSITION, 0, 0, 1e12)],
  reject_index_out_of_range: ['v', (g) => {
    const p = prim(g), n = g.json.accessors[p.attributes.POSITION].count;
    g.bin.writeUInt32LE(n, at(g, p.indices, 1));
  }],
  reject_index_huge: ['v', (g) => g.bin.writeUInt32LE(0xffffffff, at(g, prim(g, 1).indices, 0))],
  reject_indices_uint16: ['v', (g) => { g.json.accessors[prim(g).indices].componentType = 5123; }],
  reject_index_count_not_triangles: ['v', (g) => { g.json.accessors[prim(g).indices].count -= 1; }],
  reject_position_count_short: ['v', (g) => { g.json.accessors[prim(g).attributes.POSITION].count -= 1; }],
  reject_two_primitives: ['v', (g) => { g.json.meshes[0].primitives.push(structuredClone(prim(g))); }],
  reject_lines_primitive: ['v', (g) => { prim(g).mode = 1; }],
  reject_triangle_count_wrong: ['v', (g) => { prt(g).triangleCount += 1; }],
  reject_vertex_count_wrong: ['v', (g) => { prt(g).vertexCount += 1; }],
  // Accessors and buffer views.
  reject_accessor_offset_past_view: ['v', (g) => { g.json.accessors[prim(g).attributes.POSITION].byteOffset = 1 << 20; }],
  reject_bufferview_past_buffer: ['v', (g) => {
    g.json.bufferViews[g.json.accessors[prim(g).attributes.NORMAL].bufferView].byteLength += 1 << 20;
  }],
  reject_bufferview_missing: ['v', (g) => { g.json.accessors[prim(g).attributes.POSITION].bufferView = 999; }],
  reject_accessor_missing: ['v', (g) => { prim(g).attributes.NORMAL = 999; }],
  reject_stride_smaller_than_element: ['v', (g) => {
    g.json.bufferViews[g.json.accessors[prim(g).attributes.POSITION].bufferView].byteStride = 4;
  }],
  reject_sparse_accessor: ['v', (g) => {
    g.json.accessors[prim(g).attributes.POSITION].sparse = { count: 1, indices: { bufferView: 0, componentType: 5125 }, values: { bufferView: 0 } };
  }],
  reject_external_buffer: ['v', (g) => { g.json.buffers[0].uri = 'data.bin'; }],
  // Transfer rows.
  reject_transfer_bytes: ['v', (g) => { g.json.accessors[transferAcc(g)].componentType = 5121; g.json.accessors[transferAcc(g)].normalized = true; }],
  reject_transfer_vec3: ['v', (g) => { g.json.accessors[transferAcc(g)].type = 'VEC3'; }],
  reject_transfer_nan: ['v', (g) => setFloat(g, transferAcc(g), 3, 2, NaN)],
  reject_transfer_accessor_list_short: ['v', (g) => { prt(g).transfers[1].accessors.pop(); }],
  reject_two_transfers_of_one_kind: ['v', (g) => { prt(g).transfers[1].settings.mode = prt(g).transfers[0].settings.mode; }],
  reject_channels_2: ['v', (g) => { prt(g).transfers[0].settings.channels = 2; }],
  reject_samples_0: ['v', (g) => { prt(g).transfers[0].settings.samples = 0; }],
  reject_bounces_99: ['v', (g) => { prt(g).transfers[0].settings.bounces = 99; }],
  reject_partial_vertex_range: ['v', (g) => { prt(g).vertexRange = { first: 0, count: prt(g).vertexCount - 1 }; }],
  // Versions.
  reject_version_newer: ['v', (g) => { prt(g).formatVersion = 99; }],
  reject_version_4_in_extension: ['v', (g) => { prt(g).formatVersion = 4; }],
  reject_version_6_in_extras: ['v', (g) => { g.json.extras = { prtkit: prt(g) }; delete g.json.extensions; delete g.json.extensionsUsed; }],
  reject_version_5_with_texels: ['t', (g) => { prt(g).formatVersion = 5; }],
  reject_compressed_in_version_2: ['c', (g) => {
    const o = prt(g);
    o.formatVersion = 2;
    g.json.extras = { prtkit: o };
    delete g.json.extensions, delete g.json.extensionsUsed;
  }],
  // Per-texel transfer.
  reject_texel_rows_bytes: ['t', (g) => { g.json.accessors[transferAcc(g)].componentType = 5121; }],
  reject_texel_rows_short: ['t', (g) => { g.json.accessors[transferAcc(g)].count -= 1; }],
  reject_texel_rows_nan: ['t', (g) => setFloat(g, transferAcc(g), 10, 0, NaN)],
  reject_lightmap_uv_1e9: ['t', (g) => setFloat(g, prim(g, 1).attributes.TEXCOORD_0, 2, 0, 1e9)],
  reject_lightmap_uv_negative: ['t', (g) => setFloat(g, prim(g).attributes.TEXCOORD_0, 0, 1, -0.01)],
  reject_lightmap_uv_nan: ['t', (g) => setFloat(g, prim(g).attributes.TEXCOORD_0, 0, 0, NaN)],
  reject_lightmap_uv_just_past_one: ['t', (g) => setFloat(g, prim(g).attributes.TEXCOORD_0, 0, 0, 1.00001)],
  reject_lightmap_texcoord_2: ['t', (g) => { prt(g).lightmapTexCoord = 2; }],
  reject_lightmap_padding_100: ['t', (g) => { prt(g).lightmap.padding = 100; }],
  reject_lightmap_and_vertex_range: ['t', (g) => { prt(g).vertexRange = { first: 0, count: prt(g).vertexCount }; }],
  reject_texel_transfer_over_vertices: ['t', (g) => { prt(g).transfers[0].settings.domain = 'vertices'; }],
  // CPCA.
  reject_cluster_id_out_of_range: ['c', (g) => g.bin.writeUInt16LE(60000, at(g, accIndex(g, cpca(g).compressed.accessorPrefix + 'CLUSTER'), 3))],
  reject_cluster_ids_float: ['c', (g) => { g.json.accessors[accIndex(g, cpca(g).compressed.accessorPrefix + 'CLUSTER')].componentType = 5126; }],
  reject_cpca_means_nan: ['c', (g) => setFloat(g, accIndex(g, cpca(g).compressed.accessorPrefix + 'MEANS'), 1, 0, NaN)],
  reject_cpca_basis_count_too_large: ['c', (g) => { cpca(g).compressed.basisCount = 1000; }],
  reject_texel_cpca_cluster_out_of_range: ['tc', (g) => g.bin.writeUInt16LE(9999, at(g, accIndex(g, cpca(g).compressed.accessorPrefix + 'CLUSTER'), 0))],
  // Probe grids (format 7): the grid, its range, its matrices.
  accept_probes: ['p', () => {}],
  accept_probes_cpca: ['pc', () => {}],
  accept_probes_without_response: ['p', (g) => { delete prt(g).transfers[0].response; }],
  accept_probe_grid_larger_than_its_range: ['p', (g) => { prt(g).probeGrid.count[2] = 3; }],  // partial: prt web refuses
  accept_probe_spacing_uneven: ['p', (g) => { prt(g).probeGrid.spacing = [0.25, 1, 2]; }],
  accept_probe_origin_1e30: ['p', (g) => { prt(g).probeGrid.origin[1] = 1e30; }],
  reject_probe_version_6: ['p', (g) => { prt(g).formatVersion = 6; }],
  reject_probe_beside_vertex_range: ['p', (g) => { prt(g).vertexRange = { first: 0, count: prt(g).vertexCount }; }],
  reject_probe_beside_texel_range: ['p', (g) => { prt(g).lightmap = { width: 2, height: 2, padding: 0 }; prt(g).texelRange = { first: 0, count: 4 }; }],
  reject_probe_grid_missing: ['p', (g) => { delete prt(g).probeGrid; }],
  reject_probe_range_missing: ['p', (g) => { delete prt(g).probeRange; }],
  reject_probe_grid_not_object: ['p', (g) => { prt(g).probeGrid = [1, 2, 3]; }],
  reject_probe_origin_two_numbers: ['p', (g) => { prt(g).probeGrid.origin = [0, 0]; }],
  reject_probe_origin_null: ['p', (g) => { prt(g).probeGrid.origin[0] = null; }],
  reject_probe_origin_string: ['p', (g) => { prt(g).probeGrid.origin[2] = '0'; }],
  reject_probe_origin_1e31: ['p', (g) => { prt(g).probeGrid.origin[1] = 1e31; }],
  reject_probe_spacing_zero: ['p', (g) => { prt(g).probeGrid.spacing[1] = 0; }],
  reject_probe_spacing_negative: ['p', (g) => { prt(g).probeGrid.spacing[0] = -0.5; }],
  reject_probe_spacing_below_float: ['p', (g) => { prt(g).probeGrid.spacing[2] = 1e-50; }],
  reject_probe_count_zero: ['p', (g) => { prt(g).probeGrid.count[0] = 0; }],
  reject_probe_count_fraction: ['p', (g) => { prt(g).probeGrid.count[1] = 1.5; }],
  reject_probe_count_513: ['p', (g) => { prt(g).probeGrid.count[2] = 513; }],
  reject_probe_count_string: ['p', (g) => { prt(g).probeGrid.count[0] = '2'; }],
  reject_probe_grid_over_the_limit: ['p', (g) => { prt(g).probeGrid.count = [512, 512, 512]; }],
  reject_probe_range_outside_grid: ['p', (g) => { prt(g).probeRange.count = 9; }],
  reject_probe_rows_short: ['p', (g) => { prt(g).probeGrid.count[2] = 1; prt(g).probeRange.count = 4; }],
  reject_probe_matrix_accessor_short: ['p', (g) => { g.json.accessors[transferAcc(g)].count -= 1; }],
  reject_probe_matrix_nan: ['p', (g) => setFloat(g, transferAcc(g), 37, 0, NaN)],
  reject_probe_matrix_bytes: ['p', (g) => { g.json.accessors[transferAcc(g)].componentType = 5121; }],
  reject_probe_bands_3: ['p', (g) => { prt(g).transfers[0].settings.bands = 3; }],
  reject_probe_vector_layout: ['p', (g) => { prt(g).transfers[0].settings.layout = 'vector'; }],
  reject_probe_transfer_over_vertices: ['p', (g) => { prt(g).transfers[0].settings.domain = 'vertices'; }],
  reject_probe_without_transfers: ['p', (g) => { prt(g).transfers = []; }],
  reject_probe_cpca_cluster_out_of_range: ['pc', (g) => g.bin.writeUInt16LE(7, at(g, accIndex(g, cpca(g).compressed.accessorPrefix + 'CLUSTER'), 3))],
  reject_probe_cpca_basis_nan: ['pc', (g) => setFloat(g, accIndex(g, cpca(g).compressed.accessorPrefix + 'BASIS'), 5, 0, NaN)],
  // Haar transfer (format 8): its shape and its four quantised accessors (haar_bake.js; the
  // library's HaarRowsCodec and haar::checkRow), and what the browser viewers do not relight.
  accept_haar: ['h', () => {}],
  accept_haar_resolution_64: ['h', (g) => { prt(g).transfers[0].settings.haar.resolution = 64; }],
  accept_haar_per_texel: ['ht', () => {}],  // relit at the texel points prt web ships beside it
  accept_haar_cube_past_the_page: ['h128', () => {}],  // a 128² cube: prt web refuses
  reject_haar_in_version_7: ['h', (g) => { prt(g).formatVersion = 7; }],
  reject_haar_unknown_basis: ['h', (g) => { prt(g).transfers[0].settings.basis = 'wavelet'; }],
  reject_haar_resolution_3: ['h', (g) => { prt(g).transfers[0].settings.haar.resolution = 3; }],
  reject_haar_resolution_missing: ['h', (g) => { delete prt(g).transfers[0].settings.haar; }],
  reject_haar_terms_past_the_cube: ['h', (g) => { prt(g).transfers[0].settings.haar.terms = 97; }],
  reject_haar_terms_more_than_stored: ['h', (g) => { prt(g).transfers[0].settings.haar.terms += 1; }],
  reject_haar_matrix_layout: ['h', (g) => { prt(g).transfers[0].settings.layout = 'matrix'; }],
  reject_haar_channels_3: ['h', (g) => { prt(g).transfers[0].settings.channels = 3; }],
  reject_haar_accessor_list_short: ['h', (g) => { prt(g).transfers[0].accessors.pop(); }],
  reject_haar_kind_2: ['h', (g) => { g.bin.writeUInt8(2, at(g, transferAcc(g, 0, 0), 3)); }],
  reject_haar_scale_nan: ['h', (g) => setFloat(g, transferAcc(g, 0, 1), 1, 0, NaN)],
  reject_haar_scale_negative: ['h', (g) => setFloat(g, transferAcc(g, 0, 1), 2, 0, -1)],
  reject_haar_index_past_the_cube: ['h', (g) => { haarTerm(g, (i, v) => v !== 0, (i) => g.bin.writeUInt16LE(96, i)); }],
  reject_haar_indices_not_ascending: ['h', (g) => {
    const row = haarRows(g).find((x) => x.kept >= 2);
    if (!row) throw new Error('no Haar row keeps two terms');
    g.bin.writeUInt16LE(g.bin.readUInt16LE(row.index(1)), row.index(0));
  }],
  reject_haar_padding_with_an_index: ['h', (g) => {
    const row = haarRows(g).find((x) => x.kept < x.terms);
    if (!row) throw new Error('no Haar row has padding');
    g.bin.writeUInt16LE(5, row.index(row.terms - 1));
  }],
  reject_haar_value_off_the_grid: ['h', (g) => { haarTerm(g, (i, v) => v !== 0, (i, v) => g.bin.writeInt16LE(-32768, v)); }],
  reject_haar_index_floats: ['h', (g) => { g.json.accessors[transferAcc(g, 0, 2)].componentType = 5126; }],
  reject_haar_values_short: ['h', (g) => { g.json.accessors[transferAcc(g, 0, 3)].count -= 1; }],
  // Inter-reflected Haar transfer (format 9): each row's bounce in SH, a fifth accessor.
  accept_haar_interreflected: ['hi', () => {}],
  reject_haar_bounce_in_version_8: ['hi', (g) => { prt(g).formatVersion = 8; }],
  reject_haar_bounce_without_bounces: ['hi', (g) => { prt(g).transfers[0].settings.bounces = 0; }],
  reject_haar_bounce_bands_missing: ['hi', (g) => { delete prt(g).transfers[0].settings.haar.bounceBands; }],
  reject_haar_bounce_bands_6: ['hi', (g) => { prt(g).transfers[0].settings.haar.bounceBands = 6; }],
  reject_haar_bounce_bands_more_than_stored: ['hi', (g) => { prt(g).transfers[0].settings.haar.bounceBands = 3; }],
  reject_haar_bounce_on_shadowed: ['h', (g) => { prt(g).transfers[0].settings.haar.bounceBands = 2; }],
  reject_haar_bounce_nan: ['hi', (g) => setFloat(g, transferAcc(g, 0, 4), 3, 0, NaN)],
  reject_haar_bounce_short: ['hi', (g) => { g.json.accessors[transferAcc(g, 0, 4)].count -= 1; }],
  reject_haar_bounce_accessor_missing: ['hi', (g) => { prt(g).transfers[0].accessors.pop(); }],
};

/** The Haar rows of transfer 0 of g: per row its terms, how many it keeps (its non-zero values,
 *  which come first) and the byte offsets of its k-th index and value. */
function haarRows(g) {
  const t = prt(g).transfers[0], terms = t.settings.haar.terms, rows = prt(g).vertexCount;
  const out = [];
  for (let r = 0; r < rows; ++r) {
    const index = (k) => at(g, t.accessors[2], r * terms + k), value = (k) => at(g, t.accessors[3], r * terms + k);
    let kept = 0;
    for (let k = 0; k < terms; ++k) kept += g.bin.readInt16LE(value(k)) !== 0;
    out.push({ terms, kept, index, value });
  }
  return out;
}
/** Applies change(indexAt, valueAt) to the first kept term that pick(indexAt, value) takes. */
function haarTerm(g, pick, change) {
  for (const row of haarRows(g))
    for (let k = 0; k < row.kept; ++k)
      if (pick(row.index(k), g.bin.readInt16LE(row.value(k)))) return change(row.index(k), row.value(k));
  throw new Error('no Haar term to change');
}

fs.mkdirSync(out, { recursive: true });
for (const [name, [base, mutate]] of Object.entries(cases)) {
  const g = copy(bases[base]);
  mutate(g);
  fs.writeFileSync(path.join(out, `${name}.glb`), writeGlb(g));
}
// The container and the JSON text.
const v = writeGlb(copy(bases.v));
const file = (name, bytes) => fs.writeFileSync(path.join(out, `${name}.glb`), bytes);
file('reject_truncated', v.subarray(0, v.length - 577));
file('reject_truncated_header_says_more', (() => { const b = Buffer.from(v); b.writeUInt32LE(v.length + 64, 8); return b; })());
file('reject_bin_chunk_past_end', (() => {
  const b = Buffer.from(v), binAt = 20 + b.readUInt32LE(12);
  b.writeUInt32LE(b.readUInt32LE(binAt) + 64, binAt);
  return b;
})());
file('reject_container_version_1', (() => { const b = Buffer.from(v); b.writeUInt32LE(1, 4); return b; })());
file('reject_json_broken', writeGlb(copy(bases.v), JSON.stringify(bases.v.json).slice(0, -40)));
file('reject_json_too_deep', writeGlb(copy(bases.v), JSON.stringify({ ...bases.v.json, extras: { deep: JSON.parse('['.repeat(300) + ']'.repeat(300)) } })));
file('reject_not_a_bake', writeGlb({ json: { asset: { version: '2.0' } }, bin: Buffer.alloc(0) }));
file('accept_trailing_bytes', Buffer.concat([v, Buffer.alloc(16)]));
// A probe count written 2.0: JSON.parse cannot tell it from 2, so the library takes it too.
const probeText = JSON.stringify(bases.p.json).replace('"count":[2,2,2]', '"count":[2.0,2,2.0]');
if (probeText === JSON.stringify(bases.p.json)) throw new Error('the probe grid\'s counts are not [2,2,2]');
file('accept_probe_count_written_2.0', writeGlb(copy(bases.p), probeText));
console.log(`${Object.keys(cases).length + 9} cases written to ${out}`);
