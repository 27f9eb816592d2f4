#pragma once
// Guards shared by every verb (header-only, internal to the command line):
//  * outputs never overwrite inputs (or each other), compared by filesystem identity, so
//    `prt export b.glb -o ./b.glb` and hard links are caught as well as the same spelling;
//  * numeric options are range-checked with one message shape ("--bands 0: must be 1..16"),
//    non-finite values rejected, negative values for unsigned options refused before CLI11
//    wraps them;
//  * anything we echo is one short line (oneLine), whatever a file or an exception holds;
//  * "-o -" (standard output, prt/core/file.hpp) is refused in one line by a verb whose output
//    is not one stream (refuseStandardOutput).

#include <unistd.h>
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/image/color.hpp"

namespace prt::cli {

/// A named path: what the user typed and which option it came from ("-o", "--preview", "input").
struct NamedPath {
  std::string option;
  std::string path;
};

namespace detail {

inline bool isSpec(const std::string& p) {
  return p.empty() || p.rfind("builtin:", 0) == 0;  // not a file: nothing to overwrite
}

/// True when `a` and `b` name the same file: by identity (device, inode) when both exist, else
/// by their normalised absolute paths (catches "./x" vs "x" before the output exists).
inline bool sameFile(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ea, eb;
  const bool xa = fs::exists(a, ea), xb = fs::exists(b, eb);
  if (xa && xb) {
    std::error_code ec;
    const bool same = fs::equivalent(a, b, ec);
    return !ec && same;
  }
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb && ca == cb;
}

/// True when `inner` lies inside folder `dir` (or is it).
inline bool inside(const std::string& inner, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code e1, e2;
  const fs::path i = fs::weakly_canonical(fs::absolute(inner, e1), e1);
  const fs::path d = fs::weakly_canonical(fs::absolute(dir, e2), e2);
  if (e1 || e2) return false;
  auto di = d.begin(), ii = i.begin();
  for (; di != d.end(); ++di, ++ii) {
    if (di->empty()) continue;  // a trailing separator
    if (ii == i.end() || *ii != *di) return false;
  }
  return true;
}

}  // namespace detail

/// Throws one line naming both paths when an output is the same file as an input, or two
/// outputs are the same file. Empty paths and builtin:NAME are skipped. Call it before any work
/// and again with the files actually read (a face folder's images) before writing.
inline void checkOutputs(const std::vector<NamedPath>& outputs,
                         const std::vector<NamedPath>& inputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const NamedPath& o = outputs[k];
    if (detail::isSpec(o.path)) continue;
    for (const NamedPath& in : inputs)
      if (!isStandardOutput(o.path) && !detail::isSpec(in.path) &&
          detail::sameFile(o.path, in.path))
        throw Error(o.path,
                    o.option + " would overwrite the input " + in.path +
                        (in.option.empty() || in.option == "input" ? "" : " (" + in.option + ")") +
                        "; choose another output name");
    for (std::size_t j = 0; j < k; ++j)
      if (!detail::isSpec(outputs[j].path) && detail::sameFile(o.path, outputs[j].path))
        throw Error(o.path, o.option + " and " + outputs[j].option + " name the same file");
  }
}

/// For an output folder that is replaced as a whole: no input may lie inside it.
inline void checkOutputFolder(const NamedPath& folder, const std::vector<NamedPath>& inputs) {
  for (const NamedPath& in : inputs)
    if (!detail::isSpec(in.path) && detail::inside(in.path, folder.path))
      throw Error(folder.path, folder.option +
                                   " folder would be replaced, and it holds the input " + in.path +
                                   "; choose another output folder");
}

/// For an output that cannot be one stream (a folder, several files): "-o -" refused in one
/// line, "-o -: WHY; name a file".
inline void refuseStandardOutput(const NamedPath& output, const std::string& why) {
  if (isStandardOutput(output.path))
    throw Error(output.option + " -: " + why + "; name a file instead of - (standard output)");
}

/// One short line: control characters (newlines, tabs, escapes) become spaces, runs of spaces
/// collapse, and anything past `maxChars` bytes is cut (at a UTF-8 boundary) and marked "…".
inline std::string oneLine(const std::string& s, std::size_t maxChars = 300) {
  std::string out;
  out.reserve(std::min(s.size(), maxChars + 8));
  bool space = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) {
      if (!space && !out.empty()) out += ' ';
      space = true;
      continue;
    }
    if (out.size() >= maxChars) {
      // Back up to a UTF-8 lead byte so the cut does not split a character.
      while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80)
        out.pop_back();
      if (!out.empty() && static_cast<unsigned char>(out.back()) >= 0xC0) out.pop_back();
      return out + "… (" + std::to_string(s.size()) + " bytes)";
    }
    space = c == ' ';
    out += static_cast<char>(c);
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// --- numeric options ------------------------------------------------------------------------

/// Integer option in [lo, hi]: "--bands 0: must be 1..16". CLI11's own range checks print the
/// bound of an open range as a 300-digit number; this one names the option and a short range.
inline CLI::Validator intRange(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        long long v = 0;
        std::size_t used = 0;
        try {
          v = std::stoll(s, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != s.size() || s.empty()) return "'" + oneLine(s, 40) + "' is not an integer";
        if (v < lo || v > hi)
          return s + " is not in " + std::to_string(lo) + ".." + std::to_string(hi);
        return {};
      },
      "INT in " + std::to_string(lo) + ".." + std::to_string(hi), "IntRange");
}

/// A non-negative integer up to `max` (seeds, counts): refuses "-1" instead of wrapping it.
inline CLI::Validator unsignedInt(std::uint64_t max = UINT64_MAX) {
  return CLI::Validator(
      [max](std::string& s) -> std::string {
        if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
          return "'" + oneLine(s, 40) + "' is not a non-negative integer";
        const std::string m = std::to_string(max);
        const std::size_t nz = std::min(s.find_first_not_of('0'), s.size());
        const std::string digits = s.substr(nz);
        if (digits.size() > m.size() || (digits.size() == m.size() && digits > m))
          return s + " is larger than " + m;
        return {};
      },
      "UINT", "UnsignedInt");
}

/// A finite real number (rejects nan, inf and 1e999), optionally within [lo, hi].
inline CLI::Validator finite(double lo = -HUGE_VAL, double hi = HUGE_VAL) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(s, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != s.size() || s.empty() || !std::isfinite(v))
          return "'" + oneLine(s, 40) + "' is not a finite number";
        if (v < lo || v > hi) {
          char buf[96];
          std::snprintf(buf, sizeof buf, " is not in [%g, %g]", lo, hi);
          return s + buf;
        }
        return {};
      },
      "NUMBER", "Finite");
}

/// An --exposure in stops: finite and within the library's one limit (image::kMaxExposureStops).
inline CLI::Validator exposureStops() {
  return finite(-image::kMaxExposureStops, image::kMaxExposureStops);
}

/// An --exposure that may also be `auto` (image/exposure.hpp's rule, the default).
inline CLI::Validator exposureStopsOrAuto() {
  const CLI::Validator stops = exposureStops();
  return CLI::Validator(
      [stops](std::string& s) -> std::string {
        if (s == "auto") return {};
        std::string t = s;
        return stops(t);
      },
      "auto|STOPS", "ExposureOrAuto");
}
/// The value of an exposureStopsOrAuto option: nullopt for `auto`.
inline std::optional<float> exposureOption(const std::string& s) {
  if (s == "auto") return std::nullopt;
  return std::stof(s);
}

/// Every value option of every verb takes exactly one value per occurrence, so repeatable
/// options (--mode, --env) never swallow a positional: `prt bake --mode shadowed x.obj -o b.glb`
/// parses like `prt bake x.obj --mode shadowed -o b.glb`.
inline void oneValuePerOption(CLI::App& app) {
  for (CLI::Option* opt : app.get_options())
    if (opt->nonpositional()) opt->allow_extra_args(false);
  for (CLI::App* sub : app.get_subcommands({})) oneValuePerOption(*sub);
}

}  // namespace prt::cli
