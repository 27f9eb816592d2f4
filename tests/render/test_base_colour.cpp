// The base-colour texture in images (render/base_colour.hpp): the texture multiplies the drawn
// diffuse radiance per pixel, at the hit's interpolated texture UV, for per-vertex and
// per-texel shading alike; a material's kd replaces it; the glossy half of a matrix relighting
// is split off exactly (relighting is linear in kd and ks) and stays untextured.

#include <gtest/gtest.h>

#include <cmath>

#include "common/random_data.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/base_colour.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/base_colour.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/render.hpp"

namespace prt {
namespace {

/// A square x, y ∈ [−1, 1] facing +Z, texture UV u = (x + 1)/2, v = (1 − y)/2 (glTF: v = 0 at
/// the top), and lightmap UVs equal to them (for per-texel shading); a 4 × 1 texture, its left
/// half red and its right half green, and a grey albedo.
Mesh texturedSquare() {
  Mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals.assign(4, Vec3f{0, 0, 1});
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.lightmapUvs = m.uvs;
  m.albedo.assign(4, Rgb(0.5f));
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  BaseColourTexture t;
  t.image.width = 4;
  t.image.height = 1;
  t.image.rgb = {255, 0, 0, 255, 0, 0, 0, 255, 0, 0, 255, 0};
  t.name = "red-green";
  m.baseColour = t;
  return m;
}

/// The centre pixel of the image of x = ±0.5, y = 0 seen from (0, 0, 3) in a 32 × 32 frame.
Rgb shadeAt(const Mesh& mesh, const render::ShadeFn& shade, float x) {
  const auto occ = makeEmbreeOccluder(mesh);
  render::Camera cam;  // from (0, 0, 3) toward the origin, +Y up
  const render::RayGenerator gen(cam, 32, 32);
  float px = 0, py = 0;
  EXPECT_TRUE(gen.project({x, 0, 0}, px, py));
  const Ray ray = gen.ray(px, py);
  const Hit hit = occ->intersect(ray);
  EXPECT_TRUE(hit.hit);
  return hit.hit ? shade(ray, hit) : Rgb(-1.0f);
}

TEST(BaseColourRender, TextureMultipliesVertexRadiancePerPixel) {
  const Mesh m = texturedSquare();
  const std::vector<Rgb> radiance(4, Rgb(0.5f));  // the albedo times a uniform light of 1
  const render::ShadeFn plain = render::vertexRadianceShader(m, radiance);
  const render::ShadeFn textured = render::texturedShader(m, *m.baseColour, plain);
  // Control: without the texture both halves are grey.
  EXPECT_EQ(shadeAt(m, plain, -0.5f), Rgb(0.5f));
  EXPECT_EQ(shadeAt(m, plain, 0.5f), Rgb(0.5f));
  // With it: red on the left, green on the right (u = 0.25 and 0.75 fall on texel centres
  // of pure colour), the albedo's 0.5 times the texture's 1.
  const Rgb left = shadeAt(m, textured, -0.5f), right = shadeAt(m, textured, 0.5f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(left[c], c == 0 ? 0.5f : 0.0f, 1e-5f) << c;
    EXPECT_NEAR(right[c], c == 1 ? 0.5f : 0.0f, 1e-5f) << c;
  }
}

TEST(BaseColourRender, TextureMultipliesTexelRadiancePerPixel) {
  // A 4 × 4 lightmap relit white (texel vectors): the albedo and then the texture per pixel.
  const Mesh m = texturedSquare();
  const std::vector<Rgb> lightmap(16, Rgb(1.0f));
  const render::ShadeFn texels =
      render::texelRadianceShader(m, lightmap, 4, 4, render::texelAlbedo(m, Material{}));
  const render::ShadeFn textured = render::texturedShader(m, *m.baseColour, texels);
  EXPECT_EQ(shadeAt(m, texels, -0.5f), Rgb(0.5f));
  const Rgb left = shadeAt(m, textured, -0.5f), right = shadeAt(m, textured, 0.5f);
  EXPECT_NEAR(left.x, 0.5f, 1e-5f);
  EXPECT_NEAR(left.y, 0.0f, 1e-5f);
  EXPECT_NEAR(right.x, 0.0f, 1e-5f);
  EXPECT_NEAR(right.y, 0.5f, 1e-5f);
}

TEST(BaseColourRender, GlossyPartIsAddedUntextured) {
  const Mesh m = texturedSquare();
  const std::vector<Rgb> diffuse(4, Rgb(0.5f)), glossy(4, Rgb(0.25f));
  const render::ShadeFn shade =
      render::texturedShader(m, *m.baseColour, render::vertexRadianceShader(m, diffuse),
                             render::vertexRadianceShader(m, glossy));
  const Rgb left = shadeAt(m, shade, -0.5f);
  EXPECT_NEAR(left.x, 0.75f, 1e-5f);
  EXPECT_NEAR(left.y, 0.25f, 1e-5f);  // the highlight alone: the texture's green is 0 here
  EXPECT_NEAR(left.z, 0.25f, 1e-5f);
}

TEST(BaseColourRender, MaterialKdReplacesTheTexture) {
  const Mesh m = texturedSquare();
  EXPECT_EQ(render::pixelTexture(m, Material{}), &*m.baseColour);
  Material kd;
  kd.diffuse = Rgb(0.3f);
  EXPECT_EQ(render::pixelTexture(m, kd), nullptr);
  EXPECT_TRUE(render::texelAlbedo(m, kd).empty());  // the same rule for the albedo
  Mesh untextured = m;
  untextured.baseColour.reset();
  EXPECT_EQ(render::pixelTexture(untextured, Material{}), nullptr);
  untextured = m;
  untextured.uvs.clear();
  EXPECT_THROW(render::texturedShader(untextured, *m.baseColour, {}), Error);
}

// e = kd ⊙ diffuse + ks ⊙ glossy is linear in (kd, ks): the two halves splitForTexture relights
// add up to the whole, for dense matrices at every row; vectors and lobe-less materials are not
// split.
TEST(BaseColourRender, SplitHalvesAddUpToTheWholeRelighting) {
  const Mesh m = texturedSquare();
  const std::size_t rows = 4;
  const Transfer matrix = testdata::randomField(TransferLayout::Matrix, 3, 1, rows, 7);
  const Transfer vector = testdata::randomField(TransferLayout::Vector, 3, 1, rows, 8);
  Material phong = parseMaterial("phong?exponent=8&ks=0.4");
  const render::TextureSplit split = render::splitForTexture(phong, &*m.baseColour, matrix);
  ASSERT_TRUE(split.glossy.has_value());
  EXPECT_EQ(split.diffuse.specular, Rgb(0.0f));
  EXPECT_EQ(*split.glossy->diffuse, Rgb(0.0f));
  const relight::Surface surface{m.positions, m.normals, m.albedo};
  const sh::RgbSh light = testdata::randomLight(3, 9);
  const Vec3f eye{0.3f, 0.2f, 3.0f};
  const auto whole = relight::relight(matrix, light, phong, surface, eye);
  const auto d = relight::relight(matrix, light, split.diffuse, surface, eye);
  const auto g = relight::relight(matrix, light, *split.glossy, surface, eye);
  for (std::size_t r = 0; r < rows; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[r][c] + g[r][c], whole[r][c], 1e-5f) << r;
  EXPECT_GT(std::fabs(g[0].x), 1e-4f);  // the glossy half is not empty
  EXPECT_FALSE(render::splitForTexture(phong, &*m.baseColour, vector).glossy.has_value());
  EXPECT_FALSE(render::splitForTexture(Material{}, &*m.baseColour, matrix).glossy.has_value());
  EXPECT_FALSE(render::splitForTexture(phong, nullptr, matrix).glossy.has_value());
}

}  // namespace
}  // namespace prt
