// Haar transfer against the Monte Carlo reference (render/validate_haar.hpp), which knows no
// basis: under a sun the all-frequency basis relights a shadowed scene far closer than SH at 5
// bands, and the light's non-linear approximation costs little at a few hundred terms.

#include <gtest/gtest.h>

#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/validate.hpp"
#include "prt/render/validate_haar.hpp"
#include "prt/transport/bake.hpp"

namespace prt::render {
namespace {

TEST(ValidateHaar, SharperThanShUnderTheSun) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=16&subdiv=3");
  const auto occ = makeEmbreeOccluder(mesh);
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky");
  BakeSettings hs;
  hs.mode = TransferMode::Shadowed;
  hs.basis = TransferBasis::Haar;
  hs.haar = {16, 256};
  hs.samples = 4;
  const Transfer haarT = bake(mesh, *occ, hs);
  HaarValidateSettings v;
  v.lightTerms = {20, 300};
  v.reference.samples = 1024;
  const HaarValidationReport hr = validateHaar(mesh, *occ, haarT, hs, sky, v);
  ASSERT_EQ(hr.rows.size(), 3u);  // 20, 300 and the whole cube
  EXPECT_EQ(hr.rows.back().lightTerms, 1536u);
  EXPECT_NEAR(hr.rows.back().energyKept, 1.0, 1e-9);
  EXPECT_LT(hr.rows[0].energyKept, hr.rows[1].energyKept);

  BakeSettings ss;
  ss.mode = TransferMode::Shadowed;
  ss.bands = 5;
  ss.samples = 1024;
  const Transfer shT = bake(mesh, *occ, ss);
  ValidateSettings sv;
  sv.reference.samples = 1024;
  sv.bandsList = {5};
  sv.floorVertices = 64;
  const ValidationReport sr = validate(mesh, *occ, shT, ss, sky,
                                       envmap::projectEnvironment(sky, 5), sv);
  const double sh5 = sr.rows.back().relRmse, haarAll = hr.rows.back().relRmse;
  EXPECT_LT(haarAll, 0.5 * sh5) << "Haar " << haarAll << " SH " << sh5;
  EXPECT_LT(hr.rows[1].relRmse, 0.5 * sh5);
  // The same reference vertices and noise: the two tables are comparable.
  EXPECT_EQ(hr.reference.vertices, sr.reference.vertices);
  EXPECT_GT(hr.refStdErr, 0.0);
}

TEST(ValidateHaar, InterreflectedRowsMeetTheBouncedReference) {
  // The reference follows the bake's bounces. The inter-reflected rows (their bounce in SH)
  // meet it as closely as shadowed rows meet the shadowed reference; the same rows without
  // their bounce (the shadowed bake) miss it by the bounced light.
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=16&subdiv=3");
  const auto occ = makeEmbreeOccluder(mesh);
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky");
  BakeSettings ir;
  ir.mode = TransferMode::Interreflected;
  ir.bounces = 1;
  ir.basis = TransferBasis::Haar;
  ir.haar = {16, 256, 3};
  ir.samples = 2;
  ir.material.diffuse = Rgb(0.9f, 0.9f, 0.9f);
  const Transfer withBounce = bake(mesh, *occ, ir);
  BakeSettings shadowed = ir;
  shadowed.mode = TransferMode::Shadowed;
  shadowed.bounces = 0;
  shadowed.haar.bounceBands = 0;
  const Transfer direct = bake(mesh, *occ, shadowed);
  HaarValidateSettings v;
  v.lightTerms = {300};
  v.reference.samples = 1024;
  const HaarValidationReport a = validateHaar(mesh, *occ, withBounce, ir, sky, v);
  // Validated as if it were inter-reflected: the reference with its bounce, the rows without.
  const HaarValidationReport b = validateHaar(mesh, *occ, direct, ir, sky, v);
  const HaarValidationReport c = validateHaar(mesh, *occ, direct, shadowed, sky, v);
  const double withIt = a.rows.back().relRmse, without = b.rows.back().relRmse,
               own = c.rows.back().relRmse;
  EXPECT_LT(withIt, 1.3 * own + 0.01) << withIt << " vs shadowed " << own;
  EXPECT_GT(without, 2 * withIt) << without << " vs " << withIt;
  EXPECT_LT(a.rows.back().energyRel, 0.5 * b.rows.back().energyRel);
}

TEST(ValidateHaar, RefusesShTransfer) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  const auto occ = makeEmbreeOccluder(mesh);
  BakeSettings ss;
  ss.samples = 16;
  const Transfer shT = bake(mesh, *occ, ss);
  EXPECT_THROW(validateHaar(mesh, *occ, shT, ss, envmap::builtinEnvironment("builtin:sky"), {}), Error);
}

}  // namespace
}  // namespace prt::render
