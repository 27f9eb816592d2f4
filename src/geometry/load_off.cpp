// Object File Format (Geomview OFF): a header keyword (OFF, with optional prefixes C for vertex
// colours and N for normals: COFF, NOFF, CNOFF), then "nv nf ne", nv vertex lines
// "x y z [nx ny nz] [r g b [a]]", nf face lines "n i0 ... i(n-1) [face colour]". '#' starts a
// comment. Polygons are fan-triangulated; vertex order is the file's. Colours given as integers
// are 8-bit sRGB, as floats sRGB in [0, 1]; both are decoded to linear albedo.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"
#include "prt/image/color.hpp"

namespace prt::detail {

namespace {

/// Whitespace-separated tokens with '#' comments, tracking the line number for messages.
class Tokens {
 public:
  /// Whitespace other than a newline. Must agree with the token scan in next() (std::isspace),
  /// or a character that ends a token but is not skipped (a vertical tab) loops forever.
  static bool blank(char c) { return c != '\n' && std::isspace(static_cast<unsigned char>(c)); }
  Tokens(std::string_view text, const std::string& label) : s_(text), label_(label) {}

  bool next(std::string_view& tok) {
    while (pos_ < s_.size()) {
      const char c = s_[pos_];
      if (c == '#') {
        while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
      } else if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (blank(c)) {
        ++pos_;
      } else {
        break;
      }
    }
    if (pos_ >= s_.size()) return false;
    const std::size_t b = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_])) &&
           s_[pos_] != '#')
      ++pos_;
    tok = s_.substr(b, pos_ - b);
    return true;
  }
  /// True if another token lies on the current line.
  bool moreOnLine() {
    std::size_t p = pos_;
    while (p < s_.size() && blank(s_[p])) ++p;
    return p < s_.size() && s_[p] != '\n' && s_[p] != '#';
  }
  template <typename T>
  T number(const char* what) {
    std::string_view tok;
    if (!next(tok)) fail(std::string("unexpected end of file, expected ") + what);
    T x{};
    const char* b = tok.data();
    if (!tok.empty() && *b == '+') ++b;
    const auto [ptr, ec] = std::from_chars(b, tok.data() + tok.size(), x);
    if (ec != std::errc() || ptr != tok.data() + tok.size())
      fail(std::string("expected ") + what + ", found '" + std::string(tok) + "'");
    return x;
  }
  [[noreturn]] void fail(const std::string& msg) const {
    throw Error(label_, "line " + std::to_string(line_) + ": " + msg);
  }
  std::size_t remaining() const { return s_.size() - pos_; }

 private:
  std::string_view s_;
  const std::string& label_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

}  // namespace

bool isOffKeyword(std::string_view key) {
  return key.size() >= 3 && key.substr(key.size() - 3) == "OFF" &&
         key.find('4') == std::string_view::npos && key.find("ST") == std::string_view::npos;
}

Mesh readOff(const std::string& label, std::string_view text, LoadReport& report) {
  Tokens in(text, label);
  std::string_view kw;
  if (!in.next(kw)) throw Error(label, "is empty");
  std::string key(kw);
  const bool hasNormals =
      key.find('N') != std::string::npos && key.find("OFF") != std::string::npos;
  const bool hasColours =
      key.find('C') != std::string::npos && key.find("OFF") != std::string::npos;
  if (!isOffKeyword(key))
    throw Error(label, "not an OFF file (header '" + key.substr(0, 20) +
                           "'; supported: OFF, COFF, NOFF, CNOFF)");
  const long long nv = in.number<long long>("the vertex count");
  const long long nf = in.number<long long>("the face count");
  in.number<long long>("the edge count");
  // Each vertex needs at least 6 characters ("0 0 0\n"), each face 8: reject absurd counts
  // before allocating.
  if (nv < 0 || nf < 0 || std::size_t(nv) > in.remaining() / 6 + 1 ||
      std::size_t(nf) > in.remaining() / 8 + 1)
    throw Error(label, "vertex/face counts " + std::to_string(nv) + "/" + std::to_string(nf) +
                           " do not fit the file size (truncated or corrupt header)");
  checkLimit(label, "vertex count", std::uint64_t(nv), limits().maxVertices, "PRT_MAX_VERTICES");
  checkLimit(label, "face count", std::uint64_t(nf), limits().maxTriangles, "PRT_MAX_TRIANGLES");
  Mesh m;
  m.positions.resize(nv);
  if (hasNormals) m.normals.resize(nv);
  if (hasColours) m.albedo.resize(nv);
  for (long long v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) m.positions[v][k] = in.number<float>("a vertex coordinate");
    if (hasNormals)
      for (int k = 0; k < 3; ++k) m.normals[v][k] = in.number<float>("a normal component");
    if (hasColours) {
      std::string_view tok;
      float c[4] = {1, 1, 1, 1};
      int count = 0;
      bool integer = true;
      while (count < 4 && in.moreOnLine() && in.next(tok)) {
        integer &= tok.find('.') == std::string_view::npos;
        const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), c[count]);
        if (ec != std::errc() || ptr != tok.data() + tok.size() || !std::isfinite(c[count]))
          in.fail("vertex " + std::to_string(v) + " colour '" + std::string(tok.substr(0, 40)) +
                  "' is not a finite number");
        ++count;
      }
      if (count < 3) in.fail("vertex " + std::to_string(v) + " has no RGB colour");
      for (int k = 0; k < 3; ++k)
        m.albedo[v][k] = integer ? image::srgbToLinear(std::clamp(c[k], 0.0f, 255.0f) / 255.0f)
                                 : image::srgbToLinear(std::clamp(c[k], 0.0f, 1.0f));
    }
  }
  std::vector<std::uint32_t> corners;
  for (long long f = 0; f < nf; ++f) {
    const long long n = in.number<long long>("a face's corner count");
    if (n < 0 || std::size_t(n) > in.remaining())
      in.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " corners");
    corners.clear();
    for (long long k = 0; k < n; ++k) {
      const long long i = in.number<long long>("a vertex index");
      if (i < 0 || i >= nv) throwBadIndex(label, f, i, nv);
      corners.push_back(static_cast<std::uint32_t>(i));
    }
    while (in.moreOnLine()) {  // optional face colour: ignored
      std::string_view tok;
      in.next(tok);
    }
    if (n > 3) ++report.polygonsTriangulated;
    for (long long k = 1; k + 1 < n; ++k)
      m.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  return m;
}

}  // namespace prt::detail
