#pragma once
// What the headless-Chromium tests of tests/web share: finding Chromium, loading a page with a
// test hook and reading back the JSON it reports, and comparing a frame it drew with a
// prt render image as displayed. Scratch files go to the program's scratch folder ("web").

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_harness.hpp"
#include "common/scratch.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"

namespace web_harness {

namespace fs = std::filesystem;
using prt::testing::Result;

inline const fs::path& scratch() {
  return prt::testing::programScratch("web");
}

inline Result shell(const std::string& cmd) {
  const fs::path out = scratch() / "shell.out", err = scratch() / "shell.err";
  Result r;
  r.rc = std::system((cmd + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
  r.rc = WIFEXITED(r.rc) ? WEXITSTATUS(r.rc) : -1;
  r.out = prt::testing::slurp(out);
  r.err = prt::testing::slurp(err);
  return r;
}

inline std::string which(const std::vector<std::string>& names) {
  for (const std::string& n : names) {
    if (n.empty()) continue;
    if (n.find('/') != std::string::npos) {
      if (::access(n.c_str(), X_OK) == 0) return n;
      continue;
    }
    const Result r = shell("command -v '" + n + "'");
    if (r.rc == 0 && !r.out.empty()) return r.out.substr(0, r.out.find('\n'));
  }
  return "";
}

/// node, where the page's sources can run under it (three.js installed by scripts/setup.sh, the
/// generated constants.js their 'prt:' imports resolve to built), or "" and why in `why`.
inline std::string nodeForPageSources(std::string* why) {
  const fs::path source = PRT_SOURCE_DIR,
                 generated = fs::path(PRT_BINARY_DIR) / "generated" / "web";
  const std::string n = which({"node", "nodejs"});
  if (n.empty())
    *why = "no node here (apt-get install nodejs)";
  else if (!fs::exists(source / "web/node_modules/three/package.json"))
    *why = "web/node_modules missing (run scripts/setup.sh)";
  else if (!fs::exists(generated / "constants.js"))
    *why = generated.string() + "/constants.js is not built (ninja prt_web_assets)";
  else
    return n;
  return "";
}

inline const std::string& chromium() {
  static const std::string c = [] {
    const char* env = std::getenv("PRT_CHROMIUM");
    return which({env ? env : "", "chromium", "chromium-browser", "google-chrome"});
  }();
  return c;
}

/// Loads DIR/index.html?QUERY in headless Chromium and returns the JSON the page's test hook
/// wrote into <pre id="prt-test"> ("" if none; `log` gets Chromium's stderr). A run whose dump
/// holds no report at all — Chromium, loaded by the suite beside it, now and then exits before
/// the page ran (seen once in 700-odd page loads of a fresh clone's suite) — is made once more;
/// a page that reports a failure is never retried, and one that reports nothing twice returns "".
inline std::string runPageOnce(const std::string& dir, const std::string& query, std::string* log,
                               const std::string& extraFlags);
inline std::string runPage(const std::string& dir, const std::string& query,
                           std::string* log = nullptr, const std::string& extraFlags = "") {
  std::string first;
  const std::string json = runPageOnce(dir, query, &first, extraFlags);
  if (!json.empty()) {
    if (log) *log = first;
    return json;
  }
  std::string second;
  const std::string again = runPageOnce(dir, query, &second, extraFlags);
  if (log) *log = "(no report from the first Chromium run; its log:)\n" + first + second;
  return again;
}

inline std::string runPageOnce(const std::string& dir, const std::string& query, std::string* log,
                               const std::string& extraFlags) {
  const fs::path profile = scratch() / ("profile" + std::to_string(std::rand()));
  const std::string cmd =
      "timeout 120 '" + chromium() + "' --headless --no-sandbox --disable-gpu --disable-quic " +
      "--no-first-run --disable-background-networking --disable-component-update --disable-sync " +
      "--use-angle=swiftshader --enable-unsafe-swiftshader --user-data-dir='" + profile.string() +
      "' " + extraFlags + " --virtual-time-budget=60000 --dump-dom 'file://" + dir +
      "/index.html?" + query + "'";
  const Result r = shell(cmd);
  if (log) *log = r.err;
  // (std::regex recurses per character: no regex on these long strings.)
  const std::string open = "<pre id=\"prt-test\">";
  const std::size_t a = r.out.find(open);
  if (a == std::string::npos) return "";
  const std::size_t b = r.out.find("</pre>", a);
  if (b == std::string::npos) return "";
  std::string s = r.out.substr(a + open.size(), b - a - open.size());
  // --dump-dom escapes &, < and > in text; the hook's JSON holds none but messages might.
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}})
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + 1))
      s.replace(p, from.size(), to);
  return s;
}

/// The string value of "key" in flat JSON (values without escaped quotes).
inline std::string jsonField(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\":\"";
  const std::size_t a = json.find(k);
  if (a == std::string::npos) return "";
  const std::size_t b = json.find('"', a + k.size());
  return b == std::string::npos ? "" : json.substr(a + k.size(), b - a - k.size());
}

/// Bytes from standard base64 (prt::base64's, as the pages' data scripts hold them).
inline std::vector<unsigned char> unbase64(const std::string& s) {
  std::vector<unsigned char> out;
  unsigned v = 0;
  int n = 0;
  for (char c : s) {
    int d = c >= 'A' && c <= 'Z'   ? c - 'A'
            : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+'             ? 62
            : c == '/'             ? 63
                                   : -1;
    if (d < 0) continue;
    v = (v << 6) | unsigned(d);
    if ((n += 6) >= 8) out.push_back(static_cast<unsigned char>(v >> (n -= 8)));
  }
  return out;
}

inline double quantile90 = 1.0;  // of the last displayedRmse

/// RMSE between the page's RGB bytes and a prt render PNG, both as displayed ([0, 1] sRGB).
/// Also checks the interior: the 90th percentile of the per-pixel error (edges differ by
/// anti-aliasing: prt render jitters 4 samples, WebGL resolves 4× MSAA) must be < 2.5/255, as
/// tests/viewer require of prt view.
inline double displayedRmse(const std::vector<unsigned char>& rgb, const std::string& png) {
  const prt::image::Image ref = prt::image::readImage(png);
  EXPECT_EQ(rgb.size(), ref.pixels.size() * 3);
  if (rgb.size() != ref.pixels.size() * 3) return 1.0;
  double sum = 0;
  std::vector<double> pixel;
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
    const prt::Rgb& p = ref.pixels[i];
    const float want[3] = {prt::image::linearToSrgb(p.x), prt::image::linearToSrgb(p.y),
                           prt::image::linearToSrgb(p.z)};
    double e = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = rgb[3 * i + c] / 255.0 - want[c];
      e += d * d;
    }
    sum += e;
    pixel.push_back(std::sqrt(e / 3));
  }
  std::sort(pixel.begin(), pixel.end());
  quantile90 = pixel[pixel.size() * 9 / 10];
  return std::sqrt(sum / double(rgb.size()));
}

inline constexpr double kMatch = 0.02;
inline constexpr double kInterior = 2.5 / 255.0;

}  // namespace web_harness
