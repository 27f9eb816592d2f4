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
