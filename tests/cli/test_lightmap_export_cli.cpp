// Relit lightmaps for engines (issue 34; prt export --format lightmap | lightmap-sh,
// io/engine_lightmaps.hpp, docs/lightmaps.md). Each test decodes what prt export wrote the way
// the engine's shader does — the formulas written here from the engines' sources (Godot's
// scene_forward_clustered.glsl before and after 4.4, Bakery's BakerySH), not from the encoder —
// and compares, at every texel and for a set of normals, with an answer computed here from the
// bake itself: the light arriving at the texel L'_p = M_p L (its matrix, the light rotated),
// its irradiance in the encoding (sh::encodeIrradiance, evaluated by sh::evaluate) over π.
// Float EXR must agree to 1e-5 of the lightmap's largest value.

#include <gtest/gtest.h>
#include <tinyexr.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "common/glb_reader.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/rotate.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using LightmapExportCli = CliTest;

const std::string kBox = "'builtin:cornell?grid=8'";
constexpr int kRes = 16;
constexpr double kStops = 1.0;  // --exposure 1: every value doubled
const std::string kRotate = "10,60,-20";

/// A light whose 3-band radiance is exactly a non-negative quadratic per channel, so that no
/// texel's L1 exceeds what the engines' packed forms hold (|c| ≤ 2A for any light ≥ 0).
void writeLight(const std::string& path) {
  const std::array<Vec3d, 3> u = {Vec3d(0.6, 0.7, 0.2), Vec3d(-0.3, 0.9, 0.1),
                                  Vec3d(0.1, 0.8, -0.5)};
  const sh::RgbSh l = sh::projectFunctionRgb(3, [&](const Vec3d& w) {
    Rgbd out;
    const double s[3] = {1.3, 1.0, 0.8};
    for (int c = 0; c < 3; ++c) {
      const double t = dot(w, normalize(u[c]));
      out[c] = s[c] * (1.0 + 0.6 * t + 0.3 * w.y * w.y);
    }
    return out;
  });
  nlohmann::json j = {{"bands", 3}, {"coefficients", nlohmann::json::array()}};
  for (const Rgb& c : l.c) j["coefficients"].push_back({c.x, c.y, c.z});
  std::ofstream(path) << j.dump();
}

/// An RGB(A) float EXR as tinyexr reads it: RGBA per pixel, row 0 the top row.
struct Exr {
  int width = 0, height = 0;
  std::vector<float> rgba;
  Rgbd at(int layer, std::size_t texel, int layerHeight) const {
    const std::size_t i =
        (std::size_t(layer) * std::size_t(layerHeight) * std::size_t(width) + texel) * 4;
    return Rgbd(rgba[i], rgba[i + 1], rgba[i + 2]);
  }
};
Exr readExr(const fs::path& file) {
  Exr e;
  float* out = nullptr;
  const char* err = nullptr;
  EXPECT_EQ(LoadEXR(&out, &e.width, &e.height, file.string().c_str(), &err), TINYEXR_SUCCESS)
      << file << (err ? err : "");
  if (out) {
    e.rgba.assign(out, out + std::size_t(e.width) * std::size_t(e.height) * 4);
    std::free(out);
  }
  return e;
}

/// The real SH of bands 0..2 with the Condon–Shortley phase, written out (docs/conventions.md).
std::array<double, 9> sh9(const Vec3d& n) {
  const double x = n.x, y = n.y, z = n.z;
  return {0.282094791773878,
          -0.488602511902920 * y,
          0.488602511902920 * z,
          -0.488602511902920 * x,
          1.092548430592079 * x * y,
          -1.092548430592079 * y * z,
          0.315391565252520 * (3 * z * z - 1),
          -1.092548430592079 * x * z,
          0.546274215296040 * (x * x - y * y)};
}

/// Normals the decodes are compared at: the six axes and 20 spread over the sphere.
std::vector<Vec3d> normals() {
  std::vector<Vec3d> n = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 20; ++i) {
    const double z = 1 - (i + 0.5) / 10, r = std::sqrt(1 - z * z), phi = 2.399963 * i;
    n.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return n;
}

/// The L1 part f ≈ A + c·n (per channel, glTF axes) as one engine's layout decodes it.
struct L1 {
  Rgbd a;
  std::array<Vec3d, 3> c;
  Rgbd at(const Vec3d& n) const {
    return Rgbd(a.x + dot(c[0], n), a.y + dot(c[1], n), a.z + dot(c[2], n));
  }
};

/// Godot 4.4+ (scene_forward_clustered.glsl): sh_light = L0 + L0·l1·n·4 with
/// l1 = (texel − ½)·2 for layers L1n1 (n.y), L1_0 (n.z), L1p1 (n.x).
L1 decodeGodot(const Exr& e, std::size_t t) {
  L1 r;
  const Rgbd l0 = e.at(0, t, kRes), n1 = e.at(1, t, kRes), z0 = e.at(2, t, kRes),
             p1 = e.at(3, t, kRes);
  r.a = l0;
  for (int ch = 0; ch < 3; ++ch)
    r.c[ch] = Vec3d((p1[ch] - 0.5) * 2, (n1[ch] - 0.5) * 2, (z0[ch] - 0.5) * 2) * (l0[ch] * 4);
  return r;
}
/// Godot 4.0–4.3: ambient = L0·0.282095 + (L1n1 n.y + L1_0 n.z + L1p1 n.x)·0.32573.
L1 decodeGodot43(const Exr& e, std::size_t t) {
  L1 r;
  const Rgbd l0 = e.at(0, t, kRes), n1 = e.at(1, t, kRes), z0 = e.at(2, t, kRes),
             p1 = e.at(3, t, kRes);
  r.a = l0 * 0.282095;
  for (int ch = 0; ch < 3; ++ch) r.c[ch] = Vec3d(p1[ch], n1[ch], z0[ch]) * 0.32573;
  return r;
}
/// Bakery's BakerySH: L1k = (texel·2 − 1)·L0·2, sh = L0 + Σ n_k L1k, with n in Unity's axes
/// (x mirrored from glTF's): so the glTF x component of c is −L1x.
L1 decodeBakery(const Exr& l0e, const Exr& xe, const Exr& ye, const Exr& ze, std::size_t t) {
  L1 r;
  const Rgbd l0 = l0e.at(0, t, kRes), x = xe.at(0, t, kRes), y = ye.at(0, t, kRes),
             z = ze.at(0, t, kRes);
  r.a = l0;
  for (int ch = 0; ch < 3; ++ch)
    r.c[ch] = Vec3d(-(x[ch] * 2 - 1), y[ch] * 2 - 1, z[ch] * 2 - 1) * (l0[ch] * 2);
  return r;
}

/// f(n) of an encoding from its L1 part as a layout decodes it (docs/lightmaps.md): what zh3's
/// zonal term adds to A + c·n (its axis and k stored — `axis`, `k` — or derived from the L1
/// part), or Geomerics' non-linear form of the same L1 numbers; the L1 part alone otherwise.
Rgbd decodeBeyondL1(sh::IrradianceEncoding enc, const L1& l, const Vec3d& n,
                    const std::optional<Vec3d>& axis, const std::optional<Rgbd>& k) {
  Rgbd got = l.at(n);
  if (sh::isZonal(enc)) {
    Vec3d ax = axis ? *axis : l.c[0] * 0.2126 + l.c[1] * 0.7152 + l.c[2] * 0.0722;
    ax = length(ax) > 0 ? normalize(ax) : Vec3d(0, 0, 1);
    const double zonal = 3 * dot(ax, n) * dot(ax, n) - 1;
    for (int ch = 0; ch < 3; ++ch) {
      double kz = 0;
      if (k) {
        kz = (*k)[ch];
      } else if (l.a[ch] > 0) {
        const double rr = std::sqrt(3.0) / 2 * std::abs(dot(l.c[ch], ax)) / l.a[ch];
        kz = l.a[ch] * std::sqrt(5.0) / 8 * (0.08 * rr + 0.6 * rr * rr);
      }
      got[ch] += kz * zonal;
    }
  } else if (enc == sh::IrradianceEncoding::L1Geomerics) {
    for (int ch = 0; ch < 3; ++ch) {
      const double a0 = l.a[ch], len = length(l.c[ch]);
      if (a0 <= 0 || len == 0) continue;  // A + c·n
      const double s = std::min(len / (2 * a0), 1.0), p = 1 + 2 * s, alpha = (1 - s) / (1 + s),
                   q = 0.5 * (1 + dot(l.c[ch], n) / len);
      got[ch] = a0 * (alpha + (1 - alpha) * (p + 1) * std::pow(std::max(q, 0.0), p));
    }
  }
  return got;
}

/// The light and the bake's matrices, and L'_p = M_p L per texel (double sums of the stored
/// floats), rotated as --rotate rotates it.
struct Incident {
  std::vector<std::array<Rgbd, 9>> rows;
};
Incident incidentFromBake(const BakeFile& bake, const sh::RgbSh& light, const Mat3d& rotation) {
  const Transfer& m = bake.transfers[0].transfer;
  EXPECT_TRUE(m.isMatrix());
  EXPECT_EQ(m.bands(), 3);
  const sh::RgbSh lit = sh::Rotation(3, rotation).apply(light);
  const std::size_t C = std::size_t(m.channels());
  Incident out;
  out.rows.resize(m.rowCount());
  for (std::size_t p = 0; p < m.rowCount(); ++p)
    for (std::size_t i = 0; i < 9; ++i) {
      Rgbd acc(0.0);
      for (std::size_t j = 0; j < 9; ++j)
        for (std::size_t c = 0; c < 3; ++c)
          acc[c] += double(m.row(p)[(i * 9 + j) * C + (C == 1 ? 0 : c)]) * double(lit.c[j][c]);
      out.rows[p][i] = acc;
    }
  return out;
}

sh::RgbSh asLight(const std::array<Rgbd, 9>& rows) {
  sh::RgbSh s(3);
  for (int i = 0; i < 9; ++i) s.c[i] = Rgb(rows[i]);
  return s;
}

/// Whether a layout's packed L1 must give up some of a texel whose L1 part is A + c·n (Godot
/// 4.4+ holds |c_k| ≤ 4A, Bakery |c_k| ≤ 2A, with A > 0; Godot 4.0–4.3 anything), and what it
/// keeps: per channel c scaled down as a whole to fit, none where A ≤ 0 (docs/lightmaps.md).
bool clamps(int layout, const Rgbd& a, std::array<Vec3d, 3>& c) {
  if (layout == 1) return false;
  const double room = layout == 0 ? 4 : 2;
  bool any = false;
  for (int ch = 0; ch < 3; ++ch) {
    const double m = std::max({std::abs(c[ch].x), std::abs(c[ch].y), std::abs(c[ch].z)});
    if (a[ch] < 0 || (a[ch] == 0 && m > 0)) {
      c[ch] = Vec3d(0.0), any = true;
    } else if (m > room * a[ch]) {
      c[ch] = c[ch] * (room * a[ch] / m), any = true;
    }
  }
  return any;
}

// Every encoding, every layout, every texel, 26 normals. An unshadowed bake under a light that
// is nowhere negative holds the exact projection of a non-negative radiance over each texel's
// hemisphere (M_p = H(n_p)), so |c| ≤ 2A everywhere: nothing clamps and every texel must agree.
// A Monte Carlo bake need not (its matrices are H(n) minus an estimate of what is occluded, a
// control variate, and the bounces are band-limited): the texels a layout must clamp are
// counted here from the reference and must be what the manifest reports, and the others must
// still agree.
TEST_F(LightmapExportCli, LightmapShDecodesInEveryEngineLayoutToTheTexelsIrradiance) {
  writeLight(path("light.json"));
  const io::Lighting light = io::loadLighting(path("light.json"), 3);
  const std::vector<Vec3d> ns = normals();
  const double scale = std::exp2(kStops) / kPi;
  const std::size_t texels = std::size_t(kRes) * kRes;
  const char* layoutNames[3] = {"godot", "godot-4.3", "bakery"};
  for (const std::string mode : {"unshadowed", "interreflected"}) {
    ASSERT_EQ(prt("-q bake " + kBox + " --mode " + mode + " --domain texels --resolution " +
                  std::to_string(kRes) + " --samples 32 --transfer matrix -o " + mode + ".glb")
                  .rc,
              0);
    const BakeFile bake = readBake(path(mode + ".glb"));
    const Incident inc = incidentFromBake(bake, light.coefficients, rotationEulerXYZ(10, 60, -20));

    for (const sh::IrradianceEncoding enc : sh::kIrradianceEncodings) {
      const std::string name = sh::toString(enc);
      SCOPED_TRACE(mode + " " + name);
      const std::string dir = mode + "-" + name;
      const Result r = prt("export " + mode + ".glb --format lightmap-sh --encoding " + name +
                           " --engine godot,godot-4.3,bakery --light light.json --rotate " +
                           kRotate + " --exposure 1 -o " + dir + " --json " + dir + ".json");
      ASSERT_EQ(r.rc, 0) << r.err;
      const nlohmann::json manifest = nlohmann::json::parse(slurp(dir_ / dir / "lightmap.json"));
      EXPECT_EQ(manifest["encoding"], name);
      EXPECT_EQ(manifest["lightmap"]["width"], kRes);
      EXPECT_EQ(manifest["lightmap"]["texCoord"], 0);  // the box has no texture set
      const nlohmann::json report = nlohmann::json::parse(slurp(dir_ / (dir + ".json")));
      EXPECT_EQ(report["encoding"], name);
      EXPECT_EQ(report["engines"].size(), 3u);
      EXPECT_EQ(report["light"]["rotateDegrees"], nlohmann::json::array({10.0, 60.0, -20.0}));

      const fs::path d = dir_ / dir;
      const Exr godot = readExr(d / "godot.exr"), godot43 = readExr(d / "godot-4.3.exr");
      ASSERT_EQ(godot.width, kRes);
      ASSERT_EQ(godot.height, 4 * kRes);
      EXPECT_NE(slurp(d / "godot.exr.import").find("slices/vertical=4"), std::string::npos);
      const Exr b0 = readExr(d / "bakery-L0.exr"), bx = readExr(d / "bakery-L1x.exr"),
                by = readExr(d / "bakery-L1y.exr"), bz = readExr(d / "bakery-L1z.exr");
      const bool axisStored =
          enc == sh::IrradianceEncoding::ZH3Shared || enc == sh::IrradianceEncoding::ZH3Optimal;
      const bool zh3Stored = enc == sh::IrradianceEncoding::ZH3 || axisStored;
      EXPECT_EQ(fs::exists(d / "zh3.exr"), zh3Stored);
      EXPECT_EQ(fs::exists(d / "zh3-axis.exr"), axisStored);
      EXPECT_EQ(fs::exists(d / "l2.exr"), sh::shRows(enc) == 9);
      const Exr zh3 = zh3Stored ? readExr(d / "zh3.exr") : Exr();
      const Exr axes = axisStored ? readExr(d / "zh3-axis.exr") : Exr();
      const Exr l2 = sh::shRows(enc) == 9 ? readExr(d / "l2.exr") : Exr();
      if (sh::shRows(enc) == 9) {
        ASSERT_EQ(l2.height, 9 * kRes);
      }

      double worst = 0, largest = 0;
      std::size_t clamped[3] = {0, 0, 0}, compared = 0;
      for (std::size_t t = 0; t < texels; ++t) {
        const sh::EncodedIrradiance e = sh::encodeIrradiance(asLight(inc.rows[t]), enc);
        // The reference's own L1 part, to say which layouts must clamp this texel.
        Rgbd a;
        std::array<Vec3d, 3> c;
        for (int ch = 0; ch < 3; ++ch) {
          a[ch] = e.sh[0][ch] * 0.282094791773878 * scale;
          c[ch] = Vec3d(-e.sh[3][ch], -e.sh[1][ch], e.sh[2][ch]) * (0.488602511902920 * scale);
        }
        const L1 layouts[3] = {decodeGodot(godot, t), decodeGodot43(godot43, t),
                               decodeBakery(b0, bx, by, bz, t)};
        for (int k = 0; k < 3; ++k) {
          std::array<Vec3d, 3> kept = c;
          const bool clamp = clamps(k, a, kept);
          clamped[k] += clamp;
          if (clamp) {
            // The L1 part the layout kept: A as it was, c fitted with its direction.
            for (int ch = 0; ch < 3; ++ch) {
              worst = std::max(worst, std::abs(layouts[k].a[ch] - a[ch]));
              worst = std::max(worst, length(layouts[k].c[ch] - kept[ch]));
            }
            continue;
          }
          ++compared;
          const L1& l = layouts[k];
          for (const Vec3d& n : ns) {
            const Rgbd want = sh::evaluate(e, n) * scale;
            largest = std::max({largest, std::abs(want.x), std::abs(want.y), std::abs(want.z)});
            // What each encoding adds to (or makes of) the L1 part, as docs/lightmaps.md says.
            Rgbd got = decodeBeyondL1(
                enc, l, n, axisStored ? std::optional<Vec3d>(Vec3d(axes.at(0, t, kRes)))
                                      : std::nullopt,
                zh3Stored ? std::optional<Rgbd>(zh3.at(0, t, kRes)) : std::nullopt);
            if (sh::shRows(enc) == 9) {
              // l2.exr alone: f = Σ_i layer_i Y_i(n).
              got = Rgbd(0.0);
              const std::array<double, 9> y = sh9(n);
              for (int i = 0; i < 9; ++i) got += l2.at(i, t, kRes) * y[i];
            }
            worst = std::max(worst, length(got - want));
          }
        }
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(manifest["clampedTexels"][layoutNames[k]], clamped[k]) << layoutNames[k];
        if (mode == "unshadowed") {
          EXPECT_EQ(clamped[k], 0u) << layoutNames[k];
        }
      }
      std::printf(
          "%-14s %-17s worst |decoded - E/pi| %.3g of %.3g over %zu texel layouts; "
          "clamped: godot %zu, bakery %zu\n",
          mode.c_str(), name.c_str(), worst, largest, compared, clamped[0], clamped[2]);
      EXPECT_GT(compared, 2 * texels);
      EXPECT_GT(largest, 0.1);
      EXPECT_LE(worst, 1e-5 * largest);
    }
  }
}

// --format lightmap: f = E(n_p)/π per texel, the albedo left out. A vector bake writes Σ_i T_i L_i
// (white); a matrix bake its diffuse part Σ_i (A_l/π) Y_i(n_p) L'_p,i at each texel's normal.
TEST_F(LightmapExportCli, PlainLightmapIsTheWhiteSurfacesRadiance) {
  writeLight(path("light.json"));
  const io::Lighting light = io::loadLighting(path("light.json"), 3);
  const Mat3d rotation = rotationEulerXYZ(10, 60, -20);
  const sh::RgbSh lit = sh::Rotation(3, rotation).apply(light.coefficients);
  const std::size_t texels = std::size_t(kRes) * kRes;
  const double scale = std::exp2(kStops);
  for (const std::string layout : {"vector", "matrix"}) {
    SCOPED_TRACE(layout);
    const std::string glb = layout + ".glb";
    ASSERT_EQ(prt("-q bake " + kBox + " --mode interreflected --domain texels --resolution " +
                  std::to_string(kRes) + " --samples 32 --transfer " + layout + " -o " + glb)
                  .rc,
              0);
    const Result r = prt("export " + glb + " --format lightmap --light light.json --rotate " +
                         kRotate + " --exposure 1 -o lm-" + layout);
    ASSERT_EQ(r.rc, 0) << r.err;
    EXPECT_NE(r.err.find("lightmap.exr"), std::string::npos) << r.err;
    const fs::path d = dir_ / ("lm-" + layout);
    EXPECT_TRUE(fs::exists(d / "lightmap.png"));
    const nlohmann::json manifest = nlohmann::json::parse(slurp(d / "lightmap.json"));
    EXPECT_EQ(manifest["kind"], "lightmap");
    EXPECT_EQ(manifest["exposure"]["scale"], 2.0);
    const Exr lm = readExr(d / "lightmap.exr");
    ASSERT_EQ(lm.width * lm.height, int(texels));

    const BakeFile bake = readBake(path(glb));
    const Transfer& tr = bake.transfers[0].transfer;
    std::vector<Vec3f> texelNormals;
    Incident inc;
    if (tr.isMatrix()) {
      const auto occ = makeEmbreeOccluder(bake.mesh);
      texelNormals = render::texelRowPoints(bake.mesh, *occ, bake.lightmap(), false).normals;
      inc = incidentFromBake(bake, light.coefficients, rotation);
    }
    double worst = 0, largest = 0;
    for (std::size_t t = 0; t < texels; ++t) {
      Rgbd want(0.0);
      if (tr.isMatrix()) {
        const std::array<double, 9> y = sh9(Vec3d(texelNormals[t]));
        const double band[9] = {1, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25};
        for (int i = 0; i < 9; ++i) want += inc.rows[t][i] * (band[i] * y[i]);
      } else {
        const std::size_t C = std::size_t(tr.channels());
        for (std::size_t i = 0; i < 9; ++i)
          for (std::size_t c = 0; c < 3; ++c)
            want[c] += double(tr.row(t)[i * C + (C == 1 ? 0 : c)]) * double(lit.c[i][c]);
      }
      want = want * scale;
      largest = std::max({largest, want.x, want.y, want.z});
      worst = std::max(worst, length(lm.at(0, t, kRes) - want));
    }
    std::printf("lightmap (%s bake): worst %.3g of %.3g\n", layout.c_str(), worst, largest);
    EXPECT_GT(largest, 0.1);
    EXPECT_LE(worst, 1e-5 * largest);
  }
}

// -o NAME.glb: the mesh and PRTKIT_lightmap, whose float layers decode (as the extension's
// README writes the decode, here from its layer names) to the encoding at every texel and
// normal; and the plain lightmap's layer is lightmap.exr's values exactly.
TEST_F(LightmapExportCli, GltfLightmapLayersDecodeToTheTexelsIrradiance) {
  writeLight(path("light.json"));
  const io::Lighting light = io::loadLighting(path("light.json"), 3);
  const std::vector<Vec3d> ns = normals();
  const double scale = std::exp2(kStops) / kPi;
  const std::size_t texels = std::size_t(kRes) * kRes;
  ASSERT_EQ(prt("-q bake " + kBox + " --mode interreflected --domain texels --resolution " +
                std::to_string(kRes) + " --samples 32 --transfer matrix -o m.glb")
                .rc,
            0);
  const BakeFile bake = readBake(path("m.glb"));
  const Incident inc = incidentFromBake(bake, light.coefficients, rotationEulerXYZ(10, 60, -20));
  const std::string relight = " --light light.json --rotate " + kRotate + " --exposure 1";
  for (const sh::IrradianceEncoding enc : sh::kIrradianceEncodings) {
    const std::string name = sh::toString(enc);
    SCOPED_TRACE(name);
    const Result r = prt("export m.glb --format lightmap-sh --encoding " + name + relight +
                         " -o " + name + ".glb --json " + name + ".json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const Glb glb = splitGlb(slurp(path(name + ".glb")));
    EXPECT_EQ(glb.json["extensionsUsed"], nlohmann::json({"PRTKIT_lightmap"}));
    EXPECT_FALSE(glb.json.contains("extensionsRequired"));
    EXPECT_EQ(glb.json["meshes"].size(), bake.mesh.parts.empty() ? 1u : bake.mesh.parts.size());
    const nlohmann::json& ext = glb.json["extensions"]["PRTKIT_lightmap"];
    EXPECT_EQ(ext["kind"], "lightmap-sh");
    EXPECT_EQ(ext["encoding"], name);
    EXPECT_EQ(ext["lightmap"]["width"], kRes);
    EXPECT_EQ(ext["lightmap"]["texCoord"], 0);
    EXPECT_TRUE(glb.json["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
    const nlohmann::json report = nlohmann::json::parse(slurp(path(name + ".json")));
    EXPECT_EQ(report["outputs"], nlohmann::json({name + ".glb"}));
    std::map<std::string, std::vector<float>> layer;
    for (const nlohmann::json& l : ext["layers"]) {
      layer[l["name"]] = accessorFloats(glb, l["accessor"]);
      ASSERT_EQ(layer[l["name"]].size(), 3 * texels) << l["name"];
    }
    EXPECT_EQ(report["layers"].size(), layer.size());
    const auto rgb = [&](const std::string& n, std::size_t t) {
      const std::vector<float>& v = layer.at(n);
      return Rgbd(v[3 * t], v[3 * t + 1], v[3 * t + 2]);
    };
    const bool l2 = sh::shRows(enc) == 9;
    EXPECT_EQ(layer.count("sh8"), l2 ? 1u : 0u);
    EXPECT_EQ(layer.count("L0"), l2 ? 0u : 1u);
    const bool axisStored =
        enc == sh::IrradianceEncoding::ZH3Shared || enc == sh::IrradianceEncoding::ZH3Optimal;
    EXPECT_EQ(layer.count("zonal"), enc == sh::IrradianceEncoding::ZH3 || axisStored);
    EXPECT_EQ(layer.count("axis"), axisStored);
    double worst = 0, largest = 0;
    for (std::size_t t = 0; t < texels; ++t) {
      const sh::EncodedIrradiance e = sh::encodeIrradiance(asLight(inc.rows[t]), enc);
      L1 l;
      if (!l2) {
        l.a = rgb("L0", t);
        const Rgbd x = rgb("L1x", t), y = rgb("L1y", t), z = rgb("L1z", t);
        for (int ch = 0; ch < 3; ++ch) l.c[ch] = Vec3d(x[ch], y[ch], z[ch]);
      }
      if (enc == sh::IrradianceEncoding::ZH3Shared) {
        // One zonal number a texel: k = s A in every channel, so an engine stores s alone.
        const Rgbd k = rgb("zonal", t);
        if (l.a[1] > 1e-4) {
          const double s = k[1] / l.a[1];
          for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(k[ch], s * l.a[ch], 1e-5 * std::abs(s * l.a[ch]) + 1e-9) << t;
        }
      }
      for (const Vec3d& n : ns) {
        const Rgbd want = sh::evaluate(e, n) * scale;
        largest = std::max({largest, std::abs(want.x), std::abs(want.y), std::abs(want.z)});
        Rgbd got(0.0);
        if (l2) {
          const std::array<double, 9> y = sh9(n);
          for (int i = 0; i < 9; ++i) got += rgb("sh" + std::to_string(i), t) * y[i];
        } else {
          got = decodeBeyondL1(
              enc, l, n,
              layer.count("axis") ? std::optional<Vec3d>(Vec3d(rgb("axis", t))) : std::nullopt,
              layer.count("zonal") ? std::optional<Rgbd>(rgb("zonal", t)) : std::nullopt);
        }
        worst = std::max(worst, length(got - want));
      }
    }
    std::printf("glTF %-17s worst |decoded - E/pi| %.3g of %.3g\n", name.c_str(), worst, largest);
    EXPECT_GT(largest, 0.1);
    EXPECT_LE(worst, 1e-5 * largest);
  }

  // The plain lightmap: its one layer f holds lightmap.exr's floats, value for value.
  ASSERT_EQ(prt("-q export m.glb --format lightmap" + relight + " -o lm").rc, 0);
  ASSERT_EQ(prt("-q export m.glb --format lightmap" + relight + " -o lm.glb").rc, 0);
  const Glb glb = splitGlb(slurp(path("lm.glb")));
  const nlohmann::json& ext = glb.json["extensions"]["PRTKIT_lightmap"];
  EXPECT_EQ(ext["kind"], "lightmap");
  ASSERT_EQ(ext["layers"].size(), 1u);
  EXPECT_EQ(ext["layers"][0]["name"], "f");
  const std::vector<float> f = accessorFloats(glb, ext["layers"][0]["accessor"]);
  const Exr lm = readExr(dir_ / "lm" / "lightmap.exr");
  ASSERT_EQ(f.size(), 3 * texels);
  for (std::size_t t = 0; t < texels; ++t)
    for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(f[3 * t + ch], lm.rgba[4 * t + ch]) << t;

  // --engine picks a folder's packed layouts: refused with a .glb, nothing written.
  expectCleanFailure("export m.glb --format lightmap-sh --engine godot -o out/x.glb",
                     "--engine picks the engines' packed layouts");
}

// What cannot be a lightmap is refused in one line naming the file, writing nothing.
TEST_F(LightmapExportCli, RefusesWhatHasNoLightmapInOneLine) {
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --samples 8 -o v.glb").rc, 0);
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode shadowed --domain texels --resolution 8 "
                "--samples 8 -o t.glb")
                .rc,
            0);
  expectCleanFailure("export v.glb --format lightmap -o out/x", "v.glb: holds per-vertex transfer");
  expectCleanFailure("export v.glb --format lightmap-sh -o out/x",
                     "v.glb: holds per-vertex transfer");
  expectCleanFailure("export t.glb --format lightmap-sh -o out/x",
                     "t.glb: holds no matrix transfer");
  expectCleanFailure("export t.glb --format lightmap --encoding zh3 -o out/x", "--encoding");
  expectCleanFailure("export t.glb --format lightmap-sh --encoding l3 -o out/x", "'l3'");
  expectCleanFailure("export t.glb --format lightmap-sh --engine unreal -o out/x",
                     "--engine 'unreal'");
  expectCleanFailure("export t.glb --format exr --light builtin:sky -o out/x", "--light");
  expectCleanFailure("export t.glb --format lightmap --light missing.exr -o out/x", "missing.exr");
}

}  // namespace
}  // namespace prt
