// The Preetham sky and the builtin environments: conventions, units and errors.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/sky.hpp"
#include "prt/image/color.hpp"

using namespace prt;
using namespace prt::envmap;

TEST(Sky, SunDirectionConvention) {
  EXPECT_GT(PreethamSky(SkyParams{3, 90, 0}).sunDirection().y, 0.9999f);
  const Vec3f north = PreethamSky(SkyParams{3, 0, 0}).sunDirection();
  EXPECT_NEAR(north.z, -1, 1e-6);  // azimuth 0 looks along −Z
  const Vec3f east = PreethamSky(SkyParams{3, 0, 90}).sunDirection();
  EXPECT_NEAR(east.x, 1, 1e-6);  // azimuth 90 along +X
  const Vec3f s = PreethamSky(SkyParams{3, 30, 120}).sunDirection();
  EXPECT_NEAR(std::asin(s.y) * 180 / kPi, 30, 1e-4);
}

TEST(Sky, ZenithLuminanceIsTheScaleAndSkyIsPhysical) {
  for (double t : {2.0, 3.0, 6.0})
    for (double e : {10.0, 45.0, 80.0}) {
      SkyParams p{t, e, 200};
      p.skyScale = 2.5;
      const PreethamSky sky(p);
      EXPECT_NEAR(image::luminance(sky.sky(Vec3f(0, 1, 0))), 2.5, 0.02) << t << " " << e;
      const Vec3f sun = sky.sunDirection();
      // Circumsolar region brighter than the sky opposite the sun at the same elevation.
      const Vec3f near = normalize(sun + Vec3f(0, 0.05f, 0));
      const Vec3f opposite = normalize(Vec3f(-sun.x, near.y, -sun.z));
      EXPECT_GT(image::luminance(sky.sky(near)), image::luminance(sky.sky(opposite)));
      for (float y : {-0.9f, -0.1f, 0.0f, 0.3f, 1.0f}) {
        const Rgb c = sky.sky(normalize(Vec3f(0.4f, y, -0.7f)));
        EXPECT_TRUE(isFinite(c));
        EXPECT_GE(std::min({c.x, c.y, c.z}), 0.0f);
      }
    }
}

TEST(Sky, SunPowerIsTheDiscIntegralTimesTransmittance) {
  SkyParams p{3, 90, 0};
  p.sunPower = 10;
  const Cap c = PreethamSky(p).sunCap();
  EXPECT_LT(c.power().x, 10.0f);        // extinction
  EXPECT_GT(c.power().x, c.power().z);  // blue scattered more than red
  p.elevationDeg = 5;
  EXPECT_LT(PreethamSky(p).sunCap().power().x, c.power().x);  // longer path at low sun
  p.elevationDeg = -10;
  EXPECT_EQ(PreethamSky(p).sunCap().power().x, 0.0f);  // set sun
}

TEST(Builtin, ParsesParametersAndRejectsBadOnes) {
  EXPECT_TRUE(isBuiltin("builtin:sky"));
  EXPECT_FALSE(isBuiltin("sky.hdr"));
  const Environment c = builtinEnvironment("builtin:constant?r=1&g=2&b=0.5", 16);
  EXPECT_EQ(c.lookup(Vec3f(0, 0, 1)), Rgb(1, 2, 0.5f));
  const Environment sky = builtinEnvironment("builtin:sky?turbidity=4&elevation=60&azimuth=10", 32);
  EXPECT_EQ(sky.caps().size(), 1u);
  EXPECT_NO_THROW(builtinEnvironment("builtin:studio?intensity=2", 32));
  auto message = [](const std::string& spec) {
    try {
      builtinEnvironment(spec, 16);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("builtin:moon").find("unknown builtin environment 'moon'"), std::string::npos);
  EXPECT_NE(message("builtin:sky?turbidty=3").find("unknown parameter 'turbidty'"),
            std::string::npos);
  EXPECT_NE(message("builtin:sky?turbidity=abc").find("needs a finite number"), std::string::npos);
  EXPECT_NE(message("builtin:sky?turbidity=100").find("builtin:sky?turbidity=100: "),
            std::string::npos);
  EXPECT_NE(message("builtin:constant?value=-1").find(">= 0"), std::string::npos);
}
