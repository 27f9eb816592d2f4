#include "prt/io/pass_file.hpp"

#include <algorithm>
#include <cstring>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/json.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt {

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'P', 'A', 'S', 'S', '2'};
/// Pass files before the checksum (refused: a flipped byte in them went unnoticed).
constexpr char kMagicWithoutChecksum[8] = {'P', 'R', 'T', 'P', 'A', 'S', 'S', '1'};
/// Magic, header length, checksum.
constexpr std::size_t kPrefix = 24;

/// FNV-1a of everything after the prefix: the header (identity, pass, shape, rays) and the rows.
std::uint64_t checksumOf(const unsigned char* bytes, std::size_t size) {
  Fnv1a h;
  h.add(bytes, size);
  return h.value();
}

std::size_t sumSize(const PassPiece& p) {
  return p.sumChannels ? p.shape.rows.count * static_cast<std::size_t>(p.shape.coeffs()) *
                             static_cast<std::size_t>(p.sumChannels)
                       : 0;
}

void check(const PassPiece& p, const std::string& name) {
  p.shape.check(name);
  if (p.pass < 0 || p.pass >= p.passes)
    throw Error(name, "pass " + std::to_string(p.pass) + " of " + std::to_string(p.passes));
  if (p.values.size() != p.shape.rows.count * p.shape.stride() || p.sum.size() != sumSize(p) ||
      p.variance.size() != p.shape.rows.count ||
      p.rays.size() != static_cast<std::size_t>(p.pass) + 1 || p.seconds.size() != p.rays.size())
    throw Error(name, "the pass file's arrays do not fit its rows");
}

}  // namespace

std::string encodePassPiece(const PassPiece& p) {
  check(p, "pass file");
  Json j;
  j["identity"] = p.identity;
  j["pass"] = p.pass;
  j["passes"] = p.passes;
  j["name"] = p.name;
  j["layout"] = toString(p.shape.layout);
  if (p.shape.domain == TransferDomain::Texels) {
    j["domain"] = toString(p.shape.domain);
    j["lightmap"] = {{"width", p.shape.lightmap.width},
                     {"height", p.shape.lightmap.height},
                     {"padding", p.shape.lightmap.padding}};
  }
  j["bands"] = p.shape.bands;
  j["channels"] = p.shape.channels;
  j["first"] = p.shape.rows.first;
  j["count"] = p.shape.rows.count;
  j["sumChannels"] = p.sumChannels;
  j["rays"] = p.rays;
  j["seconds"] = p.seconds;
  std::string header = j.dump();
  header.resize((header.size() + 7) / 8 * 8, ' ');
  std::string out(kMagic, 8);
  const std::uint64_t n = header.size();
  out.append(reinterpret_cast<const char*>(&n), 8);
  out.append(8, '\0');  // the checksum, below
  out += header;
  out.append(reinterpret_cast<const char*>(p.values.data()), p.values.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(p.sum.data()), p.sum.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(p.variance.data()), p.variance.size() * sizeof(double));
  const std::uint64_t sum =
      checksumOf(reinterpret_cast<const unsigned char*>(out.data()) + kPrefix, out.size() - kPrefix);
  std::memcpy(out.data() + 16, &sum, 8);
  return out;
}

PassPiece decodePassPiece(std::span<const unsigned char> b, const std::string& name) {
  if (b.size() >= 8 && std::memcmp(b.data(), kMagicWithoutChecksum, 8) == 0)
    throw Error(name, "is a pass file of an older prt, without a checksum: bake the pass again");
  if (b.size() < kPrefix || std::memcmp(b.data(), kMagic, 8) != 0)
    throw Error(name, "is not a pass file (prt bake --pass K writes them)");
  std::uint64_t n, checksum;
  std::memcpy(&n, b.data() + 8, 8);
  std::memcpy(&checksum, b.data() + 16, 8);
  if (n > b.size() - kPrefix) throw Error(name, "is truncated (its header runs past the end)");
  PassPiece p;
  try {
    const Json j =
        Json::parse(b.begin() + kPrefix, b.begin() + kPrefix + static_cast<std::ptrdiff_t>(n));
    p.identity = j.at("identity").get<std::string>();
    p.pass = j.at("pass").get<int>();
    p.passes = j.at("passes").get<int>();
    p.name = j.at("name").get<std::string>();
    p.shape.layout = parseTransferLayout(j.at("layout").get<std::string>());
    // Per texel (absent: per vertex, as every pass file before the texel domain).
    if (j.contains("domain")) {
      p.shape.domain = parseTransferDomain(j.at("domain").get<std::string>());
      if (p.shape.domain == TransferDomain::Texels) {
        const Json& lm = j.at("lightmap");
        p.shape.lightmap.width = lm.at("width").get<int>();
        p.shape.lightmap.height = lm.at("height").get<int>();
        p.shape.lightmap.padding = lm.at("padding").get<int>();
        if (p.shape.lightmap.width < 1 || p.shape.lightmap.width > kMaxLightmapSide ||
            p.shape.lightmap.height < 1 || p.shape.lightmap.height > kMaxLightmapSide ||
            p.shape.lightmap.padding < 0 || p.shape.lightmap.padding > kMaxLightmapPadding)
          throw Error(name, "bad pass file header (lightmap size)");
      }
    }
    p.shape.bands = j.at("bands").get<int>();
    p.shape.channels = j.at("channels").get<int>();
    p.shape.rows = {j.at("first").get<std::size_t>(), j.at("count").get<std::size_t>()};
    if (p.shape.domain == TransferDomain::Texels &&
        (p.shape.rows.count > p.shape.lightmap.texels() ||
         p.shape.rows.first > p.shape.lightmap.texels() - p.shape.rows.count))
      throw Error(name, "bad pass file header (rows outside the lightmap)");
    p.sumChannels = j.at("sumChannels").get<int>();
    p.rays = j.at("rays").get<std::vector<std::uint64_t>>();
    p.seconds = j.at("seconds").get<std::vector<double>>();
  } catch (const Error& e) {
    // Ours name the file; a parser's ("unknown transfer layout ...") is of its header.
    if (std::string(e.what()).rfind(name + ": ", 0) == 0) throw;
    throw Error(name, std::string("bad pass file header (") + e.what() + ")");
  } catch (const std::exception& e) {
    throw Error(name, std::string("bad pass file header (") + e.what() + ")");
  }
  p.shape.check(name);
  if (p.sumChannels != 0 && p.sumChannels != 1 && p.sumChannels != 3)
    throw Error(name, "bad pass file header (sumChannels)");
  const std::size_t rows = p.shape.rows.count;
  // Every row holds at least its 8-byte variance: a count past that is a lie (and the products
  // below cannot overflow).
  if (rows > b.size() / sizeof(double))
    throw Error(name, "declares " + std::to_string(rows) + " rows, more than its bytes hold");
  const std::size_t nv = rows * p.shape.stride(), ns = sumSize(p);
  const std::size_t at = kPrefix + n;
  if (b.size() - at != (nv + ns) * sizeof(float) + rows * sizeof(double))
    throw Error(name, "is truncated or too long for its " + std::to_string(rows) + " rows");
  // Every byte after the prefix, the header's and the rows', as written (checked once the
  // header says how long the file is, so a cut file is called truncated, not damaged).
  if (checksum != checksumOf(b.data() + kPrefix, b.size() - kPrefix))
    throw Error(name, "is damaged: its checksum does not match its bytes (bake the pass again)");
  std::vector<float> values(nv), sum(ns);
  std::memcpy(values.data(), b.data() + at, nv * sizeof(float));
  std::memcpy(sum.data(), b.data() + at + nv * sizeof(float), ns * sizeof(float));
  p.variance.resize(rows);
  std::memcpy(p.variance.data(), b.data() + at + (nv + ns) * sizeof(float), rows * sizeof(double));
  p.values = FloatArray(std::move(values));
  p.sum = FloatArray(std::move(sum));
  check(p, name);
  return p;
}

void writePassPiece(const std::string& path, const PassPiece& piece) {
  writeFileAtomically(path, encodePassPiece(piece));
}

PassPiece readPassPiece(const std::string& path) {
  const std::vector<unsigned char> b = readFileBytes(path);
  return decodePassPiece(b, path);
}

PassPiece mergePassPieces(std::vector<PassPiece> pieces) {
  if (pieces.empty()) throw Error("merge: no pass files");
  std::sort(pieces.begin(), pieces.end(), [](const PassPiece& a, const PassPiece& b) {
    return a.shape.rows.first < b.shape.rows.first;
  });
  PassPiece out = pieces.front();
  std::vector<float> values(out.values.begin(), out.values.end());
  std::vector<float> sum(out.sum.begin(), out.sum.end());
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const PassPiece& p = pieces[i];
    const std::string who =
        std::string("merge: the piece starting at ") + rowName(p.shape.domain) + " " +
        std::to_string(p.shape.rows.first);
    if (p.identity != out.identity) throw Error(who + " is of another bake (" + p.identity + ")");
    if (p.pass != out.pass)
      throw Error(who + " is of pass " + std::to_string(p.pass) + ", not " +
                  std::to_string(out.pass));
    TransferShape a = p.shape, b = out.shape;
    a.rows = b.rows = {};
    if (!(a == b) || p.sumChannels != out.sumChannels)
      throw Error(who + " holds rows of another shape");
    const std::size_t end = out.shape.rows.end();
    if (p.shape.rows.first < end)
      throw Error(who + " overlaps the previous range (which ends at " + std::to_string(end) + ")");
    if (p.shape.rows.first > end)
      throw Error(who + " leaves a gap: vertices " + std::to_string(end) + ".." +
                  std::to_string(p.shape.rows.first - 1) + " are missing");
    for (std::size_t k = 0; k + 1 < p.rays.size(); ++k)
      if (p.rays[k] != out.rays[k])
        throw Error(who + " read another merge of pass " + std::to_string(k));
    values.insert(values.end(), p.values.begin(), p.values.end());
    sum.insert(sum.end(), p.sum.begin(), p.sum.end());
    out.variance.insert(out.variance.end(), p.variance.begin(), p.variance.end());
    out.rays.back() += p.rays.back();
    out.seconds.back() += p.seconds.back();
    out.shape.rows.count += p.shape.rows.count;
  }
  out.values = FloatArray(std::move(values));
  out.sum = FloatArray(std::move(sum));
  return out;
}

}  // namespace prt
