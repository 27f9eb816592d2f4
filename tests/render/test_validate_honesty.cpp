// validate never prints garbage (issue 16, item 5): a zero reference gives "n/a", not 0.000 %
// (or the 1e32 % that ε alone would give); a reference or a PRT result beyond float range is
// refused with one line naming the environment or the bake, never tabulated as inf % / -nan %.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/render/render.hpp"
#include "prt/render/validate.hpp"
#include "prt/transport/bake.hpp"
#include "support/hardening.hpp"

namespace prt::render {
namespace {

using envmap::Environment;

struct Fixture {
  Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  std::unique_ptr<Occluder> occ = makeEmbreeOccluder(mesh);
  BakeSettings bake;
  Transfer transfer;
  Fixture() {
    bake.mode = TransferMode::Unshadowed;
    bake.bands = 2;
    bake.samples = 64;
    transfer = prt::bake(mesh, *occ, bake);
  }
};

Environment constant(float v, int width = 16) {
  image::Image img(width, width / 2);
  for (Rgb& p : img.pixels) p = Rgb(v);
  Environment e = Environment::latLong(img);
  e.setSource("const.exr");
  return e;
}

using test::errorOf;

TEST(ValidateHonesty, ZeroReferenceIsNotApplicableNotZeroPercent) {
  const Fixture f;
  const Environment black = constant(0.0f);
  ValidateSettings vs;
  vs.reference.samples = 16;
  // A PRT result that is not zero (a light that the black environment does not have), so the
  // old ε-only denominator would have printed an absurd percentage.
  const sh::RgbSh light = envmap::projectEnvironment(constant(1.0f), 2);
  const ValidationReport rep = validate(f.mesh, *f.occ, f.transfer, f.bake, black, light, vs);
  EXPECT_TRUE(rep.referenceIsZero);
  ASSERT_EQ(rep.rows.size(), 2u);
  EXPECT_TRUE(std::isnan(rep.rows[0].relRmse));
  EXPECT_TRUE(std::isnan(rep.rows[1].energyRel));
  const std::string table = formatTable(rep);
  EXPECT_NE(table.find("n/a"), std::string::npos) << table;
  EXPECT_NE(table.find("reference is zero"), std::string::npos) << table;
  EXPECT_EQ(table.find("inf"), std::string::npos) << table;
  EXPECT_EQ(table.find("nan"), std::string::npos) << table;
  EXPECT_EQ(table.find("0.000%"), std::string::npos) << table;
  const std::string json = reportJson(rep);
  EXPECT_NE(json.find("\"referenceIsZero\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"relRmse\": null"), std::string::npos) << json;
  bool warned = false;
  for (const std::string& w : rep.warnings)
    warned |= w.find("reference is zero") != std::string::npos;
  EXPECT_TRUE(warned);
  // A lit environment still tabulates numbers.
  const Environment lit = constant(1.0f);
  const ValidationReport ok = validate(f.mesh, *f.occ, f.transfer, f.bake, lit, light, vs);
  EXPECT_FALSE(ok.referenceIsZero);
  EXPECT_EQ(formatTable(ok).find("n/a"), std::string::npos);
  EXPECT_NE(reportJson(ok).find("\"referenceIsZero\": false"), std::string::npos);
}

TEST(ValidateHonesty, NonFiniteReferenceIsRefusedNamingTheEnvironment) {
  const Fixture f;
  // 3e38 everywhere: finite radiance whose irradiance (π · 3e38) overflows float.
  const Environment hot = constant(3e38f);
  const sh::RgbSh light = envmap::projectEnvironment(constant(1.0f), 2);
  ValidateSettings vs;
  vs.reference.samples = 16;
  const std::string e =
      errorOf([&] { validate(f.mesh, *f.occ, f.transfer, f.bake, hot, light, vs); });
  EXPECT_EQ(e.rfind("const.exr: the reference radiance at vertex ", 0), 0u) << e;
  EXPECT_NE(e.find("not finite"), std::string::npos) << e;
}

TEST(ValidateHonesty, NonFinitePrtIsRefusedNamingTheBake) {
  const Fixture f;
  const Environment lit = constant(1.0f);
  sh::RgbSh light = envmap::projectEnvironment(lit, 2);
  light.c[0] = Rgb(3e38f);  // finite, but T·L overflows float (as CPCA weights of 3e38 did)
  Transfer t = f.transfer;
  float* x = t.mutableValues();
  for (std::size_t i = 0; i < t.rowCount() * t.stride(); ++i) x[i] *= 16.0f;
  ValidateSettings vs;
  vs.reference.samples = 16;
  vs.bakeName = "given.glb";
  const std::string e = errorOf([&] { validate(f.mesh, *f.occ, t, f.bake, lit, light, vs); });
  EXPECT_EQ(e.rfind("given.glb: the PRT radiance at vertex ", 0), 0u) << e;
}

TEST(ValidateHonesty, RelitRadianceBeyondFloatIsRefusedBeforeRendering) {
  // prt render relights, then renders: an overflowed vertex (inf, or NaN from inf − inf) would
  // show black whatever the tone map, so it is refused naming the bake.
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_NO_THROW(checkFiniteRadiance(std::vector<Rgb>{Rgb(1e38f), Rgb(0.0f)}, "b.glb"));
  EXPECT_EQ(errorOf([&] {
              checkFiniteRadiance(std::vector<Rgb>{Rgb(1.0f), Rgb(inf)}, "b.glb");
            }),
            "b.glb: the relit radiance at vertex 1 is not finite (the transfer times the light "
            "overflows 32-bit floats); nothing written");
  EXPECT_NE(errorOf([&] {
              checkFiniteRadiance(std::vector<Rgb>{Rgb(std::nanf(""), 0, 0)}, "b.glb");
            }).find("vertex 0"),
            std::string::npos);
}

}  // namespace
}  // namespace prt::render
