#include "prt/io/bake_file.hpp"

// The bake file: the GLB container (glb.hpp), the mesh (bake_mesh.hpp), one codec per transfer
// representation (transfer_codecs.hpp) and the JSON of how each was made (bake_schema.hpp),
// put together here. Every size, bound and type is checked on reading, so a truncated or
// hand-edited file gives one clear line instead of a crash. Layout: docs/formats-bake.md.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>

#include "bake_mesh.hpp"
#include "bake_schema.hpp"
#include "glb.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/gltf/accessor.hpp"
#include "transfer_codecs.hpp"

namespace prt {

namespace {

using nlohmann::json;

/// "lightmap (N texels)", "grid (N probes)", "mesh (N vertices)": where a range must lie.
std::string domainExtent(TransferDomain domain, std::size_t rows) {
  switch (domain) {
    case TransferDomain::Texels:
      return "lightmap (" + std::to_string(rows) + " texels)";
    case TransferDomain::Probes:
      return "grid (" + std::to_string(rows) + " probes)";
    case TransferDomain::Vertices:
      break;
  }
  return "mesh (" + std::to_string(rows) + " vertices)";
}

json vec3Json(const Vec3f& v) {
  return json::array({v.x, v.y, v.z});
}

std::string upper(TransferMode mode) {
  std::string m = toString(mode);
  for (char& c : m) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return m;
}

void checkTransfersForWriting(const BakeFile& bake) {
  const TransferDomain domain = bake.domain();
  const std::size_t n = bake.domainRows();
  const RowRange rows = bake.rows();
  const char* row = rowName(domain);
  if (domain == TransferDomain::Texels) {
    const TransferShape::LightmapSize lm = bake.lightmap();
    if (lm.width < 1 || lm.height < 1 || lm.width > kMaxLightmapSide ||
        lm.height > kMaxLightmapSide || lm.padding < 0 || lm.padding > kMaxLightmapPadding)
      throw Error("bake file: the lightmap " + std::to_string(lm.width) + " x " +
                  std::to_string(lm.height) + " (padding " + std::to_string(lm.padding) +
                  ") is outside 1.." + std::to_string(kMaxLightmapSide) + " (padding 0.." +
                  std::to_string(kMaxLightmapPadding) + ")");
    if (bake.mesh.lightmapUvs.size() != bake.mesh.vertexCount())
      throw Error("bake file: per-texel transfer needs the mesh's lightmap UVs (it has none)");
  }
  if (domain == TransferDomain::Probes) checkProbeGrid(bake.probeGrid(), "bake file");
  if (rows.count == 0 || rows.end() > n)
    throw Error("bake file: " + std::string(row) + " range " + std::to_string(rows.first) + "+" +
                std::to_string(rows.count) + " is outside the " + domainExtent(domain, n));
  for (std::size_t i = 0; i < bake.transfers.size(); ++i) {
    const BakedTransfer& t = bake.transfers[i];
    for (std::size_t j = 0; j < i; ++j)
      if (bake.transfers[j].mode() == t.mode() &&
          bake.transfers[j].transfer.layout() == t.transfer.layout())
        throw Error(std::string("bake file: two ") + toString(t.transfer.layout()) +
                    " transfers of mode " + toString(t.mode()));
    if (t.transfer.domain() != domain ||
        (domain == TransferDomain::Texels && !(t.transfer.shape().lightmap == bake.lightmap())) ||
        (domain == TransferDomain::Probes && !(t.transfer.shape().probes == bake.probeGrid())))
      throw Error(
          "bake file: the transfers are over different domains (one bake file holds "
          "per-vertex transfer, per-texel transfer of one lightmap or one probe grid's)");
    if (t.transfer.rows() != rows)
      throw Error(std::string("bake file: the transfers cover different ") + row + " ranges");
    t.transfer.shape().check("bake file");
    try {
      checkRecipe(t.recipe);
    } catch (const Error& e) {
      throw Error(std::string("bake file: the ") + toString(t.mode()) + " transfer's " + e.what());
    }
    if (!t.transfer.compressed() && t.transfer.values().size() != rows.count * t.transfer.stride())
      throw Error(std::string("bake file: transfer rows do not match the ") + row + " range");
    if (t.transfer.isHaar()) t.transfer.check("bake file");
    if (t.transfer.compressed()) {
      t.transfer.check("bake file");
      // A cut below its basis (Transfer::cut keeps N): more basis vectors than values per row,
      // which the format (and its reader) does not hold.
      if (static_cast<std::size_t>(t.transfer.cpca().basisCount) > t.transfer.stride())
        throw Error(std::string("bake file: the ") + toString(t.mode()) +
                    " compressed transfer has " + std::to_string(t.transfer.cpca().basisCount) +
                    " basis vectors for " + std::to_string(t.transfer.stride()) +
                    " values per row (cut to fewer bands than its basis spans); write its dense "
                    "form (toDense) or compress it again");
    }
  }
}

/// Streams the bake as GLB to `os`.
void streamBake(const BakeFile& bake, std::ostream& os) {
  const std::vector<MeshPart> parts = io::partsOf(bake.mesh);
  io::checkMeshForWriting(bake.mesh, parts);
  checkTransfersForWriting(bake);
  const Mesh& mesh = bake.mesh;
  const RowRange rows = bake.rows();

  io::glb::BinaryChunk bin;
  json transfers = json::array();
  std::vector<std::pair<std::string, int>> attributes;  // a complete bake's vector columns
  for (const BakedTransfer& t : bake.transfers) {
    json entry = {{"settings", io::schema::settingsJson(t.transfer.shape(), t.recipe)},
                  {"stats", io::schema::statsJson(t.stats)}};
    if (t.transfer.isMatrix())
      entry["response"] = io::schema::responseJson(t.recipe.material, t.transfer.bands());
    const auto columns = io::codecFor(t.transfer).encode(t, bin, entry);
    if (bake.complete()) attributes.insert(attributes.end(), columns.begin(), columns.end());
    transfers.push_back(std::move(entry));
  }
  // The bounce albedo a bake used, when the mesh has none, as the material's base colour, so a
  // glTF viewer shows the surface the bake saw.
  const Rgb* baseColour = nullptr;
  for (const BakedTransfer& t : bake.transfers)
    if (t.recipe.material.diffuse) baseColour = &*t.recipe.material.diffuse;

  json gltf = {{"asset", {{"generator", bake.generator}, {"version", "2.0"}}}};
  io::encodeMesh(mesh, parts, attributes, baseColour, bin, gltf);
  gltf["accessors"] = bin.accessors();
  gltf["bufferViews"] = bin.views();
  gltf["buffers"] = json::array({{{"byteLength", bin.length()}}});
  json prt = {{"formatVersion", kBakeFormatVersion},
              {"generator", bake.generator},
              {"source", mesh.source},
              {"vertexCount", mesh.vertexCount()},
              {"triangleCount", mesh.triangleCount()}};
  if (bake.domain() == TransferDomain::Texels) {
    const TransferShape::LightmapSize lm = bake.lightmap();
    prt["lightmap"] = {{"width", lm.width}, {"height", lm.height}, {"padding", lm.padding}};
    if (lm.seamsFixed) prt["lightmap"]["seamsFixed"] = true;
    if (lm.denoised) prt["lightmap"]["denoised"] = true;
    prt["texelRange"] = {{"first", rows.first}, {"count", rows.count}};
  } else if (bake.domain() == TransferDomain::Probes) {
    const ProbeGrid g = bake.probeGrid();
    prt["probeGrid"] = {{"origin", vec3Json(g.origin)},
                        {"spacing", vec3Json(g.spacing)},
                        {"count", json::array({g.count[0], g.count[1], g.count[2]})}};
    prt["probeRange"] = {{"first", rows.first}, {"count", rows.count}};
  } else {
    prt["vertexRange"] = {{"first", rows.first}, {"count", rows.count}};
  }
  if (const int set = io::lightmapTexCoord(mesh); set >= 0) prt["lightmapTexCoord"] = set;
  if (!transfers.empty()) prt["transfers"] = std::move(transfers);
  gltf["extensionsUsed"] = json::array({kBakeExtension});
  gltf["extensions"] = {{kBakeExtension, std::move(prt)}};

  std::string text = gltf.dump();
  const std::uint64_t total = io::glb::fileBytes(text, bin);
  if (total > kMaxBakeFileBytes)
    throw Error("bake file: " + std::to_string(total >> 20) +
                " MiB exceeds the 4 GiB a GLB file can hold (bake fewer bands, or split the "
                "bake into row ranges with --range)");
  io::glb::write(os, std::move(text), bin);
}

BakeFile decode(std::span<const unsigned char> bytes, const std::string& name,
                const io::ByteKeeper& keeper) {
  const io::schema::Reader r{name};
  if (bytes.size() > kMaxBakeFileBytes) r.fail("file too large (> 4 GiB)");
  const io::glb::Chunks chunks = io::glb::split(bytes, name);
  checkJsonNesting(name, chunks.json);  // refuse deep JSON before the recursive parser
  json gltf;
  try {
    gltf = json::parse(chunks.json);
  } catch (const json::exception& e) {
    r.fail(std::string("invalid glTF JSON (") + std::string(e.what()).substr(0, 160) + ")");
  }
  if (!gltf.is_object()) r.fail("invalid glTF: the JSON is not an object");
  // The object: the extension (version 5 on), else the root's extras.prtkit (versions 1-4).
  const auto objectAt = [&](const char* parent, const char* key) -> const json* {
    if (!gltf.contains(parent) || !gltf[parent].is_object() || !gltf[parent].contains(key))
      return nullptr;
    const json& o = gltf[parent][key];
    if (!o.is_object()) r.fail(std::string(parent) + "." + key + " is not an object");
    return &o;
  };
  const json* inExtension = objectAt("extensions", kBakeExtension);
  const json* inExtras = objectAt("extras", "prtkit");
  if (!inExtension && !inExtras)
    r.fail(std::string("not a prtkit bake file (a glTF without the ") + kBakeExtension +
           " extension or extras.prtkit)");
  const json& prt = inExtension ? *inExtension : *inExtras;
  const std::string where =
      inExtension ? std::string("extensions.") + kBakeExtension : std::string("extras.prtkit");
  const auto version = r.integer(prt, "formatVersion", where, 0, 1e9);
  if (version > static_cast<std::uint64_t>(kBakeFormatVersion))
    r.fail("bake format version " + std::to_string(version) +
           " is newer than this prtkit understands (" + std::to_string(kBakeFormatVersion) + ")");
  if (inExtension && version < static_cast<std::uint64_t>(kFirstExtensionVersion))
    r.fail(where + ": format version " + std::to_string(version) +
           " predates the extension (versions 1-4 live in extras.prtkit)");
  if (!inExtension && version >= static_cast<std::uint64_t>(kFirstExtensionVersion))
    r.fail("extras.prtkit: format version " + std::to_string(version) + " belongs in the " +
           kBakeExtension + " extension");
  if (version < 1) r.fail("bake format version " + std::to_string(version) + " is invalid");

  BakeFile bake;
  bake.formatVersion = static_cast<int>(version);
  const auto text = [&](const json& o, const char* key) -> const std::string* {
    return o.is_object() && o.contains(key) && o[key].is_string()
               ? &o[key].get_ref<const std::string&>()
               : nullptr;
  };
  const json asset = gltf.contains("asset") ? gltf["asset"] : json::object();
  if (const std::string* g = text(prt, "generator"))
    bake.generator = *g;
  else if (const std::string* a = text(asset, "generator"))
    bake.generator = *a;
  const std::size_t V = r.integer(prt, "vertexCount", where, 1, 4294967295.0);
  const std::size_t T = r.integer(prt, "triangleCount", where, 1, 4294967295.0);
  checkLimit(name, "vertex count", V, limits().maxVertices, "PRT_MAX_VERTICES");
  checkLimit(name, "triangle count", T, limits().maxTriangles, "PRT_MAX_TRIANGLES");

  // A bake file is one self-contained GLB: it never names another file (a `uri` naming
  // /dev/zero or a FIFO would otherwise be read or block).
  if (gltf.contains("buffers") && gltf["buffers"].is_array())
    for (const json& b : gltf["buffers"])
      if (b.is_object() && b.contains("uri"))
        r.fail(
            "refers to an external file (" +
            (b["uri"].is_string() ? b["uri"].get<std::string>().substr(0, 80) : b["uri"].dump()) +
            "); a bake is one .glb");
  const gltf::AccessorReader ar(name, gltf::documentOf(gltf, chunks.bin, name));
  const int lightmap = r.has(prt, "lightmapTexCoord")
                           ? static_cast<int>(r.integer(prt, "lightmapTexCoord", where, 0, 1))
                           : -1;
  bake.mesh = io::decodeMesh(gltf, ar, V, T, lightmap, r);
  // The one image a bake holds: the mesh's base-colour texture (any version reads it; files
  // without one are as before).
  bake.mesh.baseColour = io::decodeBaseColour(gltf, ar, bake.mesh, r);
  checkMeshExtent(bake.mesh, name);  // named as given here, not as the bake's recorded source
  bake.mesh.source = text(prt, "source") ? *text(prt, "source") : name;

  // The domain: the mesh's vertices (vertexRange), or a lightmap's texels (format 6 on).
  TransferDomain domain = TransferDomain::Vertices;
  TransferShape::LightmapSize lightmapSize;
  std::size_t domainRows = V;
  const char* rangeKey = "vertexRange";
  if (r.has(prt, "texelRange") || r.has(prt, "lightmap")) {
    if (version < 6)
      r.fail(where + " holds per-texel transfer in a version " + std::to_string(version) +
             " file (texels need version 6)");
    if (r.has(prt, "vertexRange")) r.fail(where + " has both a vertexRange and a texelRange");
    const std::string lw = where + ".lightmap";
    const json& lm = r.member(prt, "lightmap", where);
    lightmapSize.width = static_cast<int>(r.integer(lm, "width", lw, 1, kMaxLightmapSide));
    lightmapSize.height = static_cast<int>(r.integer(lm, "height", lw, 1, kMaxLightmapSide));
    lightmapSize.padding = static_cast<int>(r.integer(lm, "padding", lw, 0, kMaxLightmapPadding));
    lightmapSize.seamsFixed = r.has(lm, "seamsFixed") && r.boolean(lm, "seamsFixed", lw);
    lightmapSize.denoised = r.has(lm, "denoised") && r.boolean(lm, "denoised", lw);
    if (lightmap < 0)
      r.fail(where +
             " holds per-texel transfer but names no lightmapTexCoord (the UVs it is over)");
    domain = TransferDomain::Texels;
    domainRows = lightmapSize.texels();
    rangeKey = "texelRange";
  }
  // Or the probes of a grid in space (format 7 on).
  ProbeGrid probeGrid;
  if (r.has(prt, "probeRange") || r.has(prt, "probeGrid")) {
    if (version < static_cast<std::uint64_t>(kFirstProbeVersion))
      r.fail(where + " holds a probe grid in a version " + std::to_string(version) +
             " file (probes need version " + std::to_string(kFirstProbeVersion) + ")");
    if (domain == TransferDomain::Texels || r.has(prt, "vertexRange"))
      r.fail(where + " has a probeRange beside a " +
             (domain == TransferDomain::Texels ? "texelRange" : "vertexRange"));
    const std::string gw = where + ".probeGrid";
    const json& g = r.member(prt, "probeGrid", where);
    const auto triple = [&](const char* key) {
      const json& a = r.member(g, key, gw);
      if (!a.is_array() || a.size() != 3) r.fail(gw + "." + key + " is not an array of 3 numbers");
      return a;
    };
    const json& origin = triple("origin");
    const json& spacing = triple("spacing");
    const json& count = triple("count");
    for (int a = 0; a < 3; ++a) {
      const std::string at = "[" + std::to_string(a) + "]";
      const auto finite = [&](const json& v, const std::string& what) {
        if (!v.is_number() || !std::isfinite(v.get<double>()) ||
            std::abs(v.get<double>()) > kMaxProbeGridNumber)
          r.fail(gw + "." + what + at + " is not a finite number");
        return v.get<float>();
      };
      probeGrid.origin[a] = finite(origin[a], "origin");
      probeGrid.spacing[a] = finite(spacing[a], "spacing");
      if (!(probeGrid.spacing[a] > 0)) r.fail(gw + ".spacing" + at + " is not positive");
      // An integral number, as Reader::integer takes one (2 and 2.0 alike: JavaScript's
      // JSON.parse, which the page's reader uses, cannot tell them apart).
      const double n = count[a].is_number() ? count[a].get<double>() : 0.0;
      if (!(n == std::floor(n)) || n < 1 || n > kMaxProbeSide)
        r.fail(gw + ".count" + at + " is not an integer in 1.." + std::to_string(kMaxProbeSide));
      probeGrid.count[a] = static_cast<int>(n);
    }
    r.within(where, [&] { checkProbeGrid(probeGrid, gw); });
    domain = TransferDomain::Probes;
    domainRows = probeGrid.probes();
    rangeKey = "probeRange";
  }
  const std::string rw = where + "." + rangeKey;
  const json& range = r.member(prt, rangeKey, where);
  RowRange rows;
  rows.first = r.integer(range, "first", rw, 0, 4294967295.0);
  rows.count = r.integer(range, "count", rw, 1, 4294967295.0);
  if (rows.end() > domainRows)
    r.fail(std::string(rowName(domain)) + " range " + std::to_string(rows.first) + "+" +
           std::to_string(rows.count) + " is outside the " + domainExtent(domain, domainRows));

  if (prt.contains("transfers")) {
    const json& ts = prt["transfers"];
    if (!ts.is_array()) r.fail(where + ".transfers is not an array");
    for (std::size_t ti = 0; ti < ts.size(); ++ti) {
      const std::string tw = where + ".transfers[" + std::to_string(ti) + "]";
      const json& t = ts[ti];
      if (!t.is_object()) r.fail(tw + " is not an object");
      BakedTransfer bt;
      TransferShape shape;
      io::schema::readSettings(r.member(t, "settings", tw), tw + ".settings", bake.formatVersion, r,
                               bt.recipe, shape);
      if (shape.domain != domain)
        r.fail(tw + ".settings.domain is " + toString(shape.domain) + " in a bake over " +
               toString(domain));
      shape.rows = rows;
      shape.lightmap = lightmapSize;
      shape.probes = domain == TransferDomain::Probes ? probeGrid : ProbeGrid{};
      if (domain == TransferDomain::Probes && shape.layout != TransferLayout::Matrix)
        r.fail(tw + " is a " + toString(shape.layout) +
               " transfer over probes (a probe holds a matrix)");
      if (bake.find(bt.mode(), shape.layout))
        r.fail(std::string("two ") + toString(shape.layout) + " transfers of mode " +
               toString(bt.mode()));
      bt.stats =
          t.contains("stats") ? io::schema::readStats(t["stats"], tw + ".stats", r) : BakeStats{};
      const io::TransferCodec& codec = io::codecFor(t, shape, bake.formatVersion, tw, r);
      bt.transfer = codec.decode(t, tw, shape, bt.mode(), ar, r, keeper);
      if (bt.transfer.compressed())
        bt.compression = io::schema::readCpcaRecord(t["compressed"], tw + ".compressed", r);
      bake.transfers.push_back(std::move(bt));
    }
  }
  if (bake.transfers.empty() && (rows.first != 0 || rows.count != domainRows))
    r.fail("a partial bake without transfers");
  if (bake.transfers.empty() && domain == TransferDomain::Texels)
    r.fail("a per-texel bake without transfers");
  if (bake.transfers.empty() && domain == TransferDomain::Probes)
    r.fail("a probe bake without transfers");
  // The UVs a per-texel bake is over: what its bake could have used (finite, inside [0, 1]²),
  // checked here so that no reader's sampling meets a corrupt one.
  if (domain == TransferDomain::Texels)
    if (const auto v = firstUvOutside(bake.mesh.lightmapUvs)) {
      const Vec2f t = bake.mesh.lightmapUvs[*v];
      r.fail("the lightmap UV of vertex " + std::to_string(*v) + " is (" + std::to_string(t.x) +
             ", " + std::to_string(t.y) +
             "), outside [0, 1]^2 (a per-texel bake's UVs lie "
             "inside it)");
    }
  return bake;
}

}  // namespace

std::string BakedTransfer::describe() const {
  return std::string(toString(recipe.mode)) + " " + toString(transfer.layout()) +
         (transfer.isHaar() ? " (Haar)" : "") + (transfer.compressed() ? " (CPCA-compressed)" : "");
}

BakeSettings BakedTransfer::settings() const {
  BakeSettings s;
  static_cast<BakeRecipe&>(s) = recipe;
  s.layout = transfer.layout();
  s.bands = transfer.bands();
  s.basis = transfer.shape().basis;
  s.haar = transfer.shape().haar;
  s.rows = transfer.rows();
  return s;
}

TransferDomain BakeFile::domain() const {
  return transfers.empty() ? TransferDomain::Vertices : transfers.front().transfer.domain();
}

TransferShape::LightmapSize BakeFile::lightmap() const {
  return domain() == TransferDomain::Texels ? transfers.front().transfer.shape().lightmap
                                            : TransferShape::LightmapSize{};
}

ProbeGrid BakeFile::probeGrid() const {
  return domain() == TransferDomain::Probes ? transfers.front().transfer.shape().probes
                                            : ProbeGrid{};
}

std::size_t BakeFile::domainRows() const {
  return transfers.empty() ? mesh.vertexCount()
                           : transfers.front().transfer.shape().domainRows(mesh.vertexCount());
}

RowRange BakeFile::rows() const {
  if (transfers.empty()) return {0, mesh.vertexCount()};
  return transfers.front().transfer.rows();
}

bool BakeFile::complete() const {
  const RowRange r = rows();
  return r.first == 0 && r.count == domainRows();
}

void BakeFile::requireComplete(const std::string& file) const {
  if (complete()) return;
  const RowRange r = rows();
  throw Error(file, "is a partial bake: it holds transfer for " +
                        std::string(toString(domain())) + " " +
                        std::to_string(r.first) + ".." + std::to_string(r.end() - 1) + " of " +
                        std::to_string(domainRows()) +
                        " only (merge the pieces with prt merge first)");
}

void BakeFile::requireSurface(const std::string& file, const std::string& use) const {
  if (domain() != TransferDomain::Probes) return;
  throw Error(file, "holds a probe grid (" + probeGrid().describe() +
                        "), the light arriving at points in space, not a surface's transfer; " +
                        use);
}

void BakeFile::requireSh(const std::string& file, const std::string& use) const {
  for (const BakedTransfer& t : transfers)
    if (t.transfer.isHaar())
      throw Error(file, "holds Haar-wavelet transfer (" + t.describe() + ", " +
                            t.transfer.shape().describe() + "); " + use +
                            " (prt render and prt validate relight Haar bakes)");
}

void BakeFile::requireVertices(const std::string& file, const std::string& use) const {
  if (domain() == TransferDomain::Vertices) return;
  requireSurface(file, use);
  const TransferShape::LightmapSize lm = lightmap();
  throw Error(file, "holds per-texel transfer (a " + std::to_string(lm.width) + " x " +
                        std::to_string(lm.height) + " lightmap); " + use);
}

const BakedTransfer* BakeFile::find(TransferMode mode, std::optional<TransferLayout> layout) const {
  for (const auto& t : transfers)
    if (t.mode() == mode && (!layout || t.transfer.layout() == *layout)) return &t;
  return nullptr;
}

std::string transferAttributePrefix(TransferMode mode) {
  return "_PRT_" + upper(mode) + "_T";
}

std::string transferMatrixName(TransferMode mode) {
  return "_PRT_" + upper(mode) + "_M";
}

std::string transferTexelName(TransferMode mode) {
  return "_PRT_" + upper(mode) + "_TEXELS";
}

std::string transferHaarPrefix(TransferMode mode) {
  return "_PRT_" + upper(mode) + "_HAAR_";
}

std::string transferCompressedPrefix(TransferMode mode) {
  return "_PRT_" + upper(mode) + "_CPCA_";
}

std::string transferStorage(const BakedTransfer& t) {
  const Transfer& x = t.transfer;
  const TransferMode mode = t.mode();
  if (x.compressed()) return "CPCA-compressed, accessors " + transferCompressedPrefix(mode) + "*";
  if (x.isHaar()) return "quantised, accessors " + transferHaarPrefix(mode) + "*";
  if (x.isMatrix()) return "accessor " + transferMatrixName(mode);
  if (x.domain() == TransferDomain::Texels) return "accessor " + transferTexelName(mode);
  return "attributes " + transferAttributePrefix(mode) + "0.." +
         std::to_string((x.stride() + 3) / 4 - 1);
}

std::string encodeBake(const BakeFile& bake) {
  std::ostringstream out;
  streamBake(bake, out);
  return out.str();
}

void writeBake(const std::string& path, const BakeFile& bake) {
  try {
    writeFileAtomically(path, [&](std::ostream& os) { streamBake(bake, os); });
  } catch (const Error& e) {
    const std::string what = e.what();
    throw Error(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
}

BakeFile decodeBake(std::span<const unsigned char> bytes, const std::string& name) {
  return decode(bytes, name, {});
}

BakeFile readBake(const std::string& path) {
  // One copy of the file in memory; dense matrices and compressed rows view it.
  auto bytes = std::make_shared<const std::vector<unsigned char>>(
      readFileBytes(path, kMaxBakeFileBytes, "the GLB format's 4 GiB"));
  return decode(*bytes, path, io::ByteKeeper{bytes});
}

BakeFile mapBake(const std::string& path) {
  const std::shared_ptr<const MappedFile> file =
      mapFile(path, kMaxBakeFileBytes, "the GLB format's 4 GiB");
  BakeFile bake = decode(file->bytes(), path, io::ByteKeeper{file, /*checkRows=*/false});
  // The mesh is read (and copied) in order; what is left to read is rows, picked anywhere.
  file->adviseRandomAccess();
  return bake;
}

std::vector<std::size_t> transferPreference(const BakeFile& bake) {
  std::vector<std::size_t> order;
  for (TransferMode m : kModesRichestFirst)
    for (TransferLayout l : {TransferLayout::Matrix, TransferLayout::Vector})
      for (std::size_t i = 0; i < bake.transfers.size(); ++i)
        if (bake.transfers[i].mode() == m && bake.transfers[i].transfer.layout() == l)
          order.push_back(i);
  return order;
}

const BakedTransfer& pickTransfer(const BakeFile& bake, std::optional<TransferMode> mode,
                                  std::optional<TransferLayout> layout, const std::string& file) {
  if (bake.transfers.empty()) throw Error(file, "the bake holds no transfer");
  for (std::size_t i : transferPreference(bake)) {
    const BakedTransfer& t = bake.transfers[i];
    if ((!mode || t.mode() == *mode) && (!layout || t.transfer.layout() == *layout)) return t;
  }
  const std::string want = std::string(mode ? toString(*mode) + std::string(" ") : "") +
                           (layout ? toString(*layout) + std::string(" ") : "");
  std::string have;
  for (const auto& t : bake.transfers)
    have += std::string(have.empty() ? "" : ", ") + toString(t.mode()) + " " +
            toString(t.transfer.layout());
  throw Error(file, "no " + want + "transfer in the bake (it has " + have + ")");
}

}  // namespace prt
