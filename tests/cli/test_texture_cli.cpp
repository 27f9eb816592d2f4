// The base-colour texture end to end (issue 18): an OBJ plane whose map_Kd is red on its left
// half and green on its right, baked and rendered under a uniform light, draws red on the left
// and green on the right — per-vertex and per-texel bakes alike, where the four vertices alone
// could only give one blend — while the same plane without the texture (the control) and with
// a material kd draws grey; a glossy matrix material's highlight stays untextured; a corrupt
// texture is one warning naming it.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli_harness.hpp"
#include "prt/image/image_io.hpp"
#include "prt/render/camera.hpp"

namespace prt {
namespace {

using namespace prt::testing;

class TextureCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    // 4 × 2 texels: columns 0-1 red, 2-3 green (the two rows alike).
    image::Srgb8Image tex;
    tex.width = 4;
    tex.height = 2;
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 4; ++x)
        tex.rgb.insert(tex.rgb.end(), {std::uint8_t(x < 2 ? 255 : 0), std::uint8_t(x < 2 ? 0 : 255),
                                       std::uint8_t(0)});
    write("tex.png", image::encodePng(tex, "tex.png"));
    write("textured.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n");
    write("plain.mtl", "newmtl m\nKd 1 1 1\n");
    write("corrupt.mtl", "newmtl m\nKd 1 1 1\nmap_Kd broken.png\n");
    write("broken.png", std::string("\x89PNG\r\n\x1a\n", 8) + "not an image");
    // The square x, y in [-1, 1] facing +Z; vt = ((x + 1)/2, (y + 1)/2), OBJ's v running up.
    for (const std::string mtl : {"textured", "plain", "corrupt"})
      write(mtl + ".obj", "mtllib " + mtl +
                              ".mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m\n"
                              "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  }

  /// Renders `bake` under the uniform white environment to linear EXR and returns the pixels
  /// at x = −0.5 and x = +0.5 on the square's middle row.
  std::pair<Rgb, Rgb> leftAndRight(const std::string& bake, const std::string& extra = "") {
    const std::string camera = "eye=0,0,3;target=0,0,0;up=0,1,0;fov=45";
    const Result r = prt("-q render " + bake + " --light builtin:constant --background none " +
                         "--size 64x48 --spp 1 --camera '" + camera + "' " + extra + " -o out.exr");
    EXPECT_EQ(r.rc, 0) << r.err;
    const image::Image img = image::readImage(path("out.exr"));
    const render::RayGenerator gen(render::parseCamera(camera, render::Camera{}), 64, 48);
    const auto at = [&](float x) {
      float px = 0, py = 0;
      EXPECT_TRUE(gen.project({x, 0, 0}, px, py));
      return img.at(int(px), int(py));
    };
    return {at(-0.5f), at(0.5f)};
  }

  static void expectRed(const Rgb& c) {
    EXPECT_GT(c.x, 0.5f) << c.x << " " << c.y << " " << c.z;
    EXPECT_LT(c.y, 0.02f * c.x);
    EXPECT_LT(c.z, 0.02f * c.x);
  }
  static void expectGreen(const Rgb& c) {
    EXPECT_GT(c.y, 0.5f) << c.x << " " << c.y << " " << c.z;
    EXPECT_LT(c.x, 0.02f * c.y);
    EXPECT_LT(c.z, 0.02f * c.y);
  }
  static void expectGrey(const Rgb& c) {
    EXPECT_GT(c.x, 0.1f) << c.x << " " << c.y << " " << c.z;
    EXPECT_NEAR(c.y, c.x, 1e-3f * c.x);
    EXPECT_NEAR(c.z, c.x, 1e-3f * c.x);
  }
};

TEST_F(TextureCli, PerVertexBakeDrawsTheTexturePerPixel) {
  for (const std::string mesh : {"textured", "plain"}) {
    const Result r =
        prt("-q bake " + mesh + ".obj --mode unshadowed --samples 64 -o " + mesh + ".glb");
    ASSERT_EQ(r.rc, 0) << r.err;
    EXPECT_EQ(r.err, "");
  }
  const auto [left, right] = leftAndRight("textured.glb");
  expectRed(left);
  expectGreen(right);
  // The control, the same plane and bake without map_Kd: grey on both sides, as bright as the
  // texture's lit channel (Kd 1 under a white furnace).
  const auto [plainLeft, plainRight] = leftAndRight("plain.glb");
  expectGrey(plainLeft);
  expectGrey(plainRight);
  EXPECT_NEAR(left.x, plainLeft.x, 1e-3f * plainLeft.x);
  EXPECT_NEAR(right.y, plainRight.y, 1e-3f * plainRight.y);
  // A material kd replaces the diffuse colour, texture included.
  const auto [kdLeft, kdRight] = leftAndRight("textured.glb", "--material 'lambert?kd=0.5'");
  expectGrey(kdLeft);
  expectGrey(kdRight);
}

TEST_F(TextureCli, PerTexelBakeDrawsTheTexturePerPixel) {
  const Result r =
      prt("-q bake textured.obj --mode unshadowed --samples 64 --domain texels "
          "--resolution 8 -o t.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto [left, right] = leftAndRight("t.glb");
  expectRed(left);
  expectGreen(right);
}

TEST_F(TextureCli, GlossyHighlightStaysUntextured) {
  const Result r =
      prt("-q bake textured.obj --mode unshadowed --samples 64 --transfer matrix --bands 3 "
          "--material 'phong?exponent=2&ks=0.3' -o g.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto [left, right] = leftAndRight("g.glb");
  // Left: kd·red + the white highlight in every channel; right: kd·green + the same highlight.
  EXPECT_GT(left.y, 0.02f) << "the highlight was tinted by the texture";
  EXPECT_NEAR(left.y, left.z, 1e-3f);
  EXPECT_GT(left.x, left.y + 0.3f);
  EXPECT_NEAR(right.x, right.z, 1e-3f);
  EXPECT_GT(right.y, right.x + 0.3f);
}

TEST_F(TextureCli, CorruptTextureIsOneWarningNamingIt) {
  const Result r = prt("bake corrupt.obj --mode unshadowed --samples 16 -o c.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto lines = std::count(r.err.begin(), r.err.end(), '\n');
  std::size_t mentions = 0;
  for (std::size_t at = r.err.find("broken.png"); at != std::string::npos;
       at = r.err.find("broken.png", at + 1))
    ++mentions;
  EXPECT_EQ(mentions, 1u) << r.err;
  EXPECT_NE(r.err.find("texture not used"), std::string::npos) << r.err;
  EXPECT_GE(lines, 1);
  const auto [left, right] = leftAndRight("c.glb");
  expectGrey(left);
  expectGrey(right);
}

}  // namespace
}  // namespace prt
