// Stanford PLY (Turk 1994): ASCII and binary little/big endian, our own small reader.
//
// Read: element "vertex" with x y z, optional nx ny nz, red green blue (8-bit sRGB, or float
// sRGB in [0, 1]; decoded to linear albedo), optional texture coordinates (u v, s t,
// texture_u texture_v); element "face" with a list property vertex_indices (or vertex_index),
// polygons fan-triangulated. Other elements and properties are skipped. Vertex order is the
// file's.
//
// Robustness: the header is checked line by line (unknown types, lists without count type,
// missing x/y/z, counts that cannot fit in the remaining bytes); binary bodies are bounds
// checked on every read, so truncated files and lying counts give one clear error instead of
// reading past the buffer or allocating absurd amounts.

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"
#include "prt/image/color.hpp"

namespace prt::detail {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

std::optional<Type> parseType(const std::string& s) {
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  return std::nullopt;
}

std::size_t sizeOf(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8:
      return 1;
    case Type::I16:
    case Type::U16:
      return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32:
      return 4;
    case Type::F64:
      return 8;
  }
  return 1;
}

bool isIntegerType(Type t) {
  return t != Type::F32 && t != Type::F64;
}

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type countType = Type::U8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

/// Reads values of the body: binary with bounds checks and byte swapping, or ASCII tokens.
class Body {
 public:
  Body(const std::string& label, const unsigned char* data, std::size_t size, Format f)
      : label_(label), p_(data), end_(data + size), format_(f) {}

  double read(Type t) {
    if (format_ == Format::Ascii) return readAscii();
    const std::size_t n = sizeOf(t);
    if (std::size_t(end_ - p_) < n)
      throw Error(label_, "truncated: data ends inside the " + where_);
    unsigned char b[8];
    std::memcpy(b, p_, n);
    p_ += n;
    const bool swap = (format_ == Format::BinaryBE) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(b, b + n);
    switch (t) {
      case Type::I8: {
        std::int8_t x;
        std::memcpy(&x, b, 1);
        return x;
      }
      case Type::U8:
        return b[0];
      case Type::I16: {
        std::int16_t x;
        std::memcpy(&x, b, 2);
        return x;
      }
      case Type::U16: {
        std::uint16_t x;
        std::memcpy(&x, b, 2);
        return x;
      }
      case Type::I32: {
        std::int32_t x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case Type::U32: {
        std::uint32_t x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case Type::F32: {
        float x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case Type::F64: {
        double x;
        std::memcpy(&x, b, 8);
        return x;
      }
    }
    return 0;
  }
  std::size_t remaining() const { return std::size_t(end_ - p_); }
  /// A list's length as read: a whole number no larger than the bytes left (every entry takes at
  /// least one byte), so a lying length fails here instead of looping or overflowing a cast.
  std::size_t listLength(double c) const {
    if (!(c >= 0) || c != std::floor(c) || c > double(remaining()))
      throw Error(label_, "in the " + where_ + ": list length " + shortNumber(c) +
                              " is not a count that fits the file");
    return std::size_t(c);
  }
  static std::string shortNumber(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
  }
  void setWhere(std::string w) { where_ = std::move(w); }

 private:
  double readAscii() {
    while (p_ < end_ && std::isspace(*p_)) ++p_;
    if (p_ == end_) throw Error(label_, "truncated: data ends inside the " + where_);
    const unsigned char* b = p_;
    while (p_ < end_ && !std::isspace(*p_)) ++p_;
    const char* s = reinterpret_cast<const char*>(b);
    const char* e = reinterpret_cast<const char*>(p_);
    if (s < e && *s == '+') ++s;
    double x = 0;
    const auto [ptr, ec] = std::from_chars(s, e, x);
    if (ec != std::errc() || ptr != e)
      throw Error(label_, "in the " + where_ + ": '" +
                              std::string(reinterpret_cast<const char*>(b), p_ - b) +
                              "' is not a number");
    return x;
  }

  const std::string& label_;
  const unsigned char* p_;
  const unsigned char* end_;
  Format format_;
  std::string where_ = "body";
};

}  // namespace

namespace {

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
};

/// The header's format and elements (the text before end_header).
Header parseHeader(const std::string& label, std::string_view text) {
  std::istringstream header{std::string(text)};
  std::string line;
  std::optional<Format> format;
  std::vector<Element> elements;
  int lineNo = 0;
  const auto bad = [&](const std::string& msg) {
    throw Error(label, "PLY header line " + std::to_string(lineNo) + ": " + msg);
  };
  while (std::getline(header, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw.empty() || kw == "ply" || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      std::string f, version;
      ls >> f >> version;
      if (f == "ascii")
        format = Format::Ascii;
      else if (f == "binary_little_endian")
        format = Format::BinaryLE;
      else if (f == "binary_big_endian")
        format = Format::BinaryBE;
      else
        bad("unknown format '" + f + "'");
    } else if (kw == "element") {
      Element e;
      long long count = -1;
      ls >> e.name >> count;
      if (e.name.empty() || !ls || count < 0) bad("malformed element line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) bad("property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        const auto c = parseType(ct), i = parseType(it);
        if (!c || !i || p.name.empty()) bad("malformed list property '" + line + "'");
        if (!isIntegerType(*c)) bad("list count type must be an integer type");
        p.list = true;
        p.countType = *c;
        p.type = *i;
      } else {
        ls >> p.name;
        const auto ty = parseType(t);
        if (!ty || p.name.empty()) bad("malformed property '" + line + "'");
        p.type = *ty;
      }
      elements.back().props.push_back(p);
    } else {
      bad("unknown keyword '" + kw + "'");
    }
  }
  if (!format) throw Error(label, "PLY header has no format line");
  return {*format, std::move(elements)};
}

/// Positions and, where the element has them, normals, sRGB colours (as linear albedo) and UVs.
void readVertices(const std::string& label, const Element& e, Body& in, Mesh& m) {
  int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, ir = -1, ig = -1, ib = -1, iu = -1,
      ivv = -1;
  for (int k = 0; k < int(e.props.size()); ++k) {
    const std::string& n = e.props[k].name;
    if (e.props[k].list) continue;
    if (n == "x")
      ix = k;
    else if (n == "y")
      iy = k;
    else if (n == "z")
      iz = k;
    else if (n == "nx")
      inx = k;
    else if (n == "ny")
      iny = k;
    else if (n == "nz")
      inz = k;
    else if (n == "red" || n == "r" || n == "diffuse_red")
      ir = k;
    else if (n == "green" || n == "g" || n == "diffuse_green")
      ig = k;
    else if (n == "blue" || n == "b" || n == "diffuse_blue")
      ib = k;
    else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
      iu = k;
    else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
      ivv = k;
  }
  if (ix < 0 || iy < 0 || iz < 0) throw Error(label, "PLY vertex element lacks x, y or z");
  const bool normals = inx >= 0 && iny >= 0 && inz >= 0;
  const bool colours = ir >= 0 && ig >= 0 && ib >= 0;
  const bool uvs = iu >= 0 && ivv >= 0;
  m.positions.resize(e.count);
  if (normals) m.normals.resize(e.count);
  if (colours) m.albedo.resize(e.count);
  if (uvs) m.uvs.resize(e.count);
  std::vector<double> val(e.props.size());
  for (std::size_t v = 0; v < e.count; ++v) {
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (p.list) {
        const std::size_t c = in.listLength(in.read(p.countType));
        for (std::size_t j = 0; j < c; ++j) in.read(p.type);
        val[k] = 0;
      } else {
        val[k] = in.read(p.type);
      }
    }
    m.positions[v] = {float(val[ix]), float(val[iy]), float(val[iz])};
    if (normals) m.normals[v] = {float(val[inx]), float(val[iny]), float(val[inz])};
    if (uvs) m.uvs[v] = {float(val[iu]), float(val[ivv])};
    if (colours) {
      const int idx[3] = {ir, ig, ib};
      for (int c = 0; c < 3; ++c) {
        const Property& p = e.props[idx[c]];
        const double x = val[idx[c]];
        // 8-bit (or 16-bit) integers are sRGB codes; floats are sRGB values in [0, 1].
        const double maxCode = p.type == Type::U16 ? 65535.0 : 255.0;
        const double s = isIntegerType(p.type) ? x / maxCode : x;
        m.albedo[v][c] = image::srgbToLinear(float(std::clamp(s, 0.0, 1.0)));
      }
    }
  }
}

/// The vertex_indices list of each face, fanned into triangles; indices checked against nv.
void readFaces(const std::string& label, const Element& e, Body& in, std::size_t nv, Mesh& m,
               LoadReport& report) {
  int li = -1;
  for (int k = 0; k < int(e.props.size()); ++k)
    if (e.props[k].list &&
        (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
      li = k;
  if (li < 0) throw Error(label, "PLY face element has no vertex_indices list");
  m.triangles.reserve(e.count);
  std::vector<std::uint32_t> corners;
  for (std::size_t f = 0; f < e.count; ++f) {
    for (int k = 0; k < int(e.props.size()); ++k) {
      const Property& p = e.props[k];
      if (!p.list) {
        in.read(p.type);
        continue;
      }
      const std::size_t n = in.listLength(in.read(p.countType));
      if (k != li) {
        for (std::size_t j = 0; j < n; ++j) in.read(p.type);
        continue;
      }
      corners.clear();
      for (std::size_t j = 0; j < n; ++j) {
        const double i = in.read(p.type);
        if (!(i >= 0 && i < double(nv) && i == std::floor(i)))
          throw Error(label, "face " + std::to_string(f) + " references vertex " +
                                 Body::shortNumber(i) + " (mesh has " + std::to_string(nv) + ")");
        corners.push_back(static_cast<std::uint32_t>(i));
      }
      if (n > 3) ++report.polygonsTriangulated;
      for (std::size_t j = 1; j + 1 < n; ++j)
        m.triangles.push_back({corners[0], corners[j], corners[j + 1]});
    }
  }
}

/// Reads past every record of an element we do not use.
void skipElement(const Element& e, Body& in) {
  for (std::size_t r = 0; r < e.count; ++r)
    for (const Property& p : e.props) {
      if (p.list) {
        const std::size_t c = in.listLength(in.read(p.countType));
        for (std::size_t j = 0; j < c; ++j) in.read(p.type);
      } else {
        in.read(p.type);
      }
    }
}

}  // namespace

Mesh readPly(const std::string& label, std::span<const unsigned char> bytes, LoadReport& report) {
  const char* text = reinterpret_cast<const char*>(bytes.data());
  const std::string_view all(text, bytes.size());
  if (all.substr(0, 3) != "ply") throw Error(label, "not a PLY file (does not start with 'ply')");
  const std::size_t endHeader = all.find("end_header");
  if (endHeader == std::string_view::npos) throw Error(label, "PLY header has no end_header");
  std::size_t bodyStart = all.find('\n', endHeader);
  if (bodyStart == std::string_view::npos)
    bodyStart = all.size();
  else
    ++bodyStart;
  const Header h = parseHeader(label, all.substr(0, endHeader));

  const unsigned char* body = bytes.data() + std::min(bodyStart, bytes.size());
  Body in(label, body, bytes.size() - std::min(bodyStart, bytes.size()), h.format);
  Mesh m;
  bool sawVertex = false, sawFace = false;
  std::size_t nv = 0;
  for (const Element& e : h.elements) {
    // The smallest possible record: reject counts that cannot fit before allocating.
    std::size_t minRecord = 0;
    for (const Property& p : e.props) minRecord += p.list ? sizeOf(p.countType) : sizeOf(p.type);
    if (h.format == Format::Ascii) minRecord = e.props.empty() ? 0 : 2 * e.props.size();
    if (minRecord && e.count > in.remaining() / minRecord)
      throw Error(label, "element '" + e.name + "' claims " + std::to_string(e.count) +
                             " records but the file has room for at most " +
                             std::to_string(in.remaining() / minRecord) + " (truncated?)");
    in.setWhere(e.name + " element");
    // An element without properties has no bytes: nothing to read, however large its count
    // (iterating 10^18 empty records would never end).
    if (e.props.empty()) {
      if (e.name == "vertex" && !sawVertex)
        throw Error(label, "PLY vertex element lacks x, y or z");
      continue;
    }
    if (e.name == "vertex" && !sawVertex) {
      checkLimit(label, "vertex count", e.count, limits().maxVertices, "PRT_MAX_VERTICES");
      sawVertex = true;
      nv = e.count;
      readVertices(label, e, in, m);
    } else if (e.name == "face" && !sawFace) {
      checkLimit(label, "face count", e.count, limits().maxTriangles, "PRT_MAX_TRIANGLES");
      if (!sawVertex) throw Error(label, "PLY face element comes before the vertex element");
      sawFace = true;
      readFaces(label, e, in, nv, m, report);
    } else {
      skipElement(e, in);
    }
  }
  if (!sawVertex) throw Error(label, "PLY file has no vertex element");
  return m;
}

}  // namespace prt::detail
