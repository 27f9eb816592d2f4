#include "prt/io/games202_transport.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"

namespace prt {

namespace {

/// True when the last character that is not a space, tab or carriage return is a newline.
bool endsWithNewline(std::string_view text) {
  std::size_t n = text.size();
  while (n > 0 && (text[n - 1] == ' ' || text[n - 1] == '\t' || text[n - 1] == '\r')) --n;
  return n > 0 && text[n - 1] == '\n';
}

}  // namespace

ChannelSelect parseChannelSelect(const std::string& s) {
  if (s == "luminance") return ChannelSelect::Luminance;
  if (s == "r") return ChannelSelect::Red;
  if (s == "g") return ChannelSelect::Green;
  if (s == "b") return ChannelSelect::Blue;
  throw Error("unknown channel '" + s + "' (expected luminance, r, g or b)");
}

Transfer selectChannel(const Transfer& field, ChannelSelect channel) {
  if (field.channels() == 1) return field;
  PRT_CHECK(field.channels() == 3, "transfer must have 1 or 3 channels");
  PRT_CHECK(!field.compressed(), "selectChannel of compressed rows");
  TransferShape shape = field.shape();
  shape.channels = 1;
  Transfer out = Transfer::zeros(shape);
  float* dst = out.mutableValues();
  const std::size_t n = field.stride() / 3;
  for (std::size_t v = 0; v < field.rowCount(); ++v)
    for (std::size_t i = 0; i < n; ++i) {
      const float* c = field.row(v) + i * 3;
      float x = 0;
      switch (channel) {
        case ChannelSelect::Luminance:
          x = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
          break;
        case ChannelSelect::Red:
          x = c[0];
          break;
        case ChannelSelect::Green:
          x = c[1];
          break;
        case ChannelSelect::Blue:
          x = c[2];
          break;
      }
      dst[v * n + i] = x;
    }
  return out;
}

std::string formatGames202Transport(const Transfer& field, const Mesh& mesh,
                                    Games202Layout layout) {
  if (field.isMatrix() || field.compressed())
    throw Error(std::string("transport.txt holds dense diffuse vectors; this transfer is ") +
                (field.isMatrix() ? "a matrix (export its diffuse part)" : "compressed") +
                " (reduce it first)");
  if (field.channels() != 1)
    throw Error(
        "transport.txt holds scalar transfer only; this transfer is RGB (reduce it to one "
        "channel first)");
  if (field.rowCount() != mesh.vertexCount() || field.rows().first != 0)
    throw Error("transport.txt: the transfer covers " + std::to_string(field.rowCount()) +
                " vertices, the mesh has " + std::to_string(mesh.vertexCount()));
  const std::size_t n = static_cast<std::size_t>(field.coeffs());
  std::string out = std::to_string(mesh.vertexCount());
  out += '\n';
  char buf[32];
  auto row = [&](std::size_t v) {
    for (std::size_t i = 0; i < n; ++i) {
      const int len = std::snprintf(buf, sizeof buf, "%.9g ", static_cast<double>(field.row(v)[i]));
      out.append(buf, static_cast<std::size_t>(len));
    }
    out += '\n';
  };
  if (layout == Games202Layout::Vertices) {
    out.reserve(out.size() + mesh.vertexCount() * n * 14);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) row(v);
  } else {
    out.reserve(out.size() + mesh.triangleCount() * 3 * n * 14);
    for (const auto& tri : mesh.triangles)
      for (std::uint32_t v : tri) {
        if (v >= mesh.vertexCount())
          throw Error("transport.txt: triangle references a missing vertex");
        row(v);
      }
  }
  return out;
}

void writeGames202Transport(const std::string& path, const Transfer& field, const Mesh& mesh,
                            Games202Layout layout) {
  std::string text;
  try {
    text = formatGames202Transport(field, mesh, layout);
  } catch (const Error& e) {
    throw Error(path, e.what());
  }
  writeFileAtomically(path, text);
}

Games202Transport parseGames202Transport(const std::string& text, const std::string& name) {
  Games202Transport t;
  std::istringstream in(text);
  std::string line;
  std::size_t lineNo = 0;
  auto fail = [&](const std::string& msg) -> void {
    throw Error(name + ":" + std::to_string(lineNo), msg);
  };
  // First non-empty line: the vertex count.
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  {
    const char* s = line.c_str();
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s, &end, 10);
    while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
    if (end == s || *end != '\0' || v <= 0 || errno != 0)
      throw Error(name, "not a transport.txt: the first line must be the vertex count, got '" +
                            line.substr(0, 40) + "'");
    t.vertexCount = static_cast<std::size_t>(v);
  }
  std::size_t perLine = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const char* s = line.c_str();
    std::size_t count = 0;
    while (true) {
      while (*s == ' ' || *s == '\t' || *s == '\r') ++s;
      if (*s == '\0') break;
      char* end = nullptr;
      const float x = std::strtof(s, &end);
      if (end == s || (*end != '\0' && *end != ' ' && *end != '\t' && *end != '\r'))
        fail("not a number: " + std::string(s, std::min<std::size_t>(std::strlen(s), 20)));
      if (!std::isfinite(x)) fail("non-finite coefficient");
      t.rows.push_back(x);
      ++count;
      s = end;
    }
    if (count == 0) continue;  // blank lines (the trailing newline)
    if (perLine == 0) {
      perLine = count;
      const int b = static_cast<int>(std::lround(std::sqrt(static_cast<double>(count))));
      if (static_cast<std::size_t>(b) * b != count)
        fail(std::to_string(count) + " coefficients per line is not a square B² (3 bands = 9)");
      t.bands = b;
    } else if (count != perLine) {
      fail(std::to_string(count) + " coefficients, previous lines have " + std::to_string(perLine));
    }
    ++t.rowCount;
  }
  if (t.rowCount == 0) throw Error(name, "no coefficient lines after the vertex count");
  // Both writers (ours, the course's) end every line with a newline: a file that stops inside a
  // line was cut short, whatever its line count says.
  if (!endsWithNewline(text))
    throw Error(name, "the last line has no newline: the file is truncated");
  // One line per vertex, or three per triangle corner — and every vertex is some triangle's
  // corner, so a faces file has at least as many lines as vertices. Fewer lines than vertices is
  // a truncated file, not the other layout.
  if (t.rowCount == t.vertexCount) {
    t.layout = Games202Layout::Vertices;
  } else if (t.rowCount % 3 == 0 && t.rowCount > t.vertexCount) {
    t.layout = Games202Layout::Faces;
  } else {
    throw Error(name, std::to_string(t.rowCount) + " coefficient lines: neither one per vertex (" +
                          std::to_string(t.vertexCount) + ") nor three per triangle corner (at " +
                          "least " + std::to_string(t.vertexCount) +
                          "); the file is truncated or corrupt");
  }
  return t;
}

Games202Transport readGames202Transport(const std::string& path) {
  const auto bytes = readFileBytes(path);
  return parseGames202Transport(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace prt
