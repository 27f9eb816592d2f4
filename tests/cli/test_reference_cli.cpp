// `prt reference -o ref.json`, read back by `prt validate --reference` and `prt render
// --reference` (io/reference_file.hpp, apps/prt/reference_input.hpp): the same table as
// computing the reference in place, and a reference of another scene refused in one line.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/image/image_io.hpp"
#include "prt/render/metrics.hpp"

namespace prt::testing {
namespace {

constexpr const char* kScene = "'builtin:sphere-plane?subdiv=1'";

class ReferenceCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const Result b = prt(std::string("-q bake ") + kScene +
                         " --mode shadowed --mode unshadowed --samples 64 -o b.glb");
    ASSERT_EQ(b.rc, 0) << b.err;
  }
  /// The report with its timing members removed (a line each, "key": value,).
  static std::string withoutSeconds(std::string s) {
    for (const char* key : {"\"referenceSeconds\"", "\"floorSeconds\"", "\"seconds\""})
      for (auto at = s.find(key); at != std::string::npos; at = s.find(key, at))
        s.erase(at, s.find('\n', at) - at + 1);
    return s;
  }
};

TEST_F(ReferenceCli, ValidateWithTheFileEqualsValidateComputingIt) {
  const std::string settings = " --light builtin:sky --rotate 0,30,0 --vertices 400 --seed 5";
  ASSERT_EQ(prt("-q reference b.glb --mode shadowed --samples 48 -o ref.json" + settings).rc, 0);
  const Result direct = prt("-q validate b.glb --mode shadowed --reference-samples 48 --json "
                            "direct.json" + settings);
  ASSERT_EQ(direct.rc, 0) << direct.err;
  const Result stored = prt("-q validate b.glb --mode shadowed --light builtin:sky --rotate "
                            "0,30,0 --reference ref.json --json stored.json");
  ASSERT_EQ(stored.rc, 0) << stored.err;
  EXPECT_EQ(stored.out, direct.out);  // the table, to the last digit
  // The reports: the same but for the reference among the inputs and the timings.
  Json a = Json::parse(withoutSeconds(slurp(dir_ / "stored.json"))),
       b = Json::parse(withoutSeconds(slurp(dir_ / "direct.json")));
  EXPECT_EQ(a["inputs"].back(), "ref.json");
  a.erase("inputs");
  b.erase("inputs");
  EXPECT_EQ(a, b) << "the reports differ beyond their inputs and timings";
}

TEST_F(ReferenceCli, AReferenceOfAnotherSceneIsRefused) {
  ASSERT_EQ(prt("-q reference b.glb --mode shadowed --light builtin:sky --samples 8 -o "
                "ref.json").rc,
            0);
  ASSERT_EQ(prt("-q bake 'builtin:sphere-plane?subdiv=2' --mode shadowed --samples 8 -o "
                "other.glb").rc,
            0);
  const std::string v = "validate b.glb --mode shadowed --reference ref.json ";
  expectCleanFailure(v + "--light builtin:studio", "was computed for the environment");
  expectCleanFailure("validate other.glb --light builtin:sky --reference ref.json",
                     "was computed for the bake");
  expectCleanFailure(v + "--light builtin:sky --rotate 0,1,0", "another light rotation");
  expectCleanFailure("validate b.glb --mode unshadowed --light builtin:sky --reference ref.json",
                     "holds shadowed transport");
  expectCleanFailure(v + "--light builtin:sky --vertices 10", "--vertices: the reference file's");
  expectCleanFailure(v + "--light builtin:sky --material 'lambert?kd=0.3'",
                     "was computed for the material");
  // A reference from before the fingerprints: says so.
  write("old.json", R"({"samples": 8, "vertices": [0], "radiance": [[1,1,1]], "stdError": [[0,0,0]]})");
  expectCleanFailure("validate b.glb --light builtin:sky --reference old.json",
                     "from before formatVersion 1");
  expectCleanFailure("render b.glb --light builtin:sky --reference ref.json --turntable 2 -o "
                     "out/f.png",
                     "--turntable");
}

TEST_F(ReferenceCli, RenderDrawsTheFilesRadiance) {
  // Unshadowed transfer of a plane under the constant sky: PRT is exact (the light is band 0
  // alone), and so is the reference (every path sees the same radiance), so the two images
  // agree; the file's radiance doubled doubles the image, so it is the file that is drawn.
  const std::string plane = "'builtin:plane?y=0&size=1'";
  ASSERT_EQ(prt("-q bake " + plane + " --mode unshadowed --samples 256 -o p.glb").rc, 0);
  ASSERT_EQ(prt("-q reference p.glb --light builtin:constant --samples 256 -o ref.json").rc, 0);
  const std::string view = " --light builtin:constant --exposure 0 --background none --size 64x48";
  ASSERT_EQ(prt("-q render p.glb -o prt.exr" + view).rc, 0);
  const Result r = prt("-q render p.glb --reference ref.json -o ref.exr" + view);
  ASSERT_EQ(r.rc, 0) << r.err;
  const image::Image a = image::readImage(path("prt.exr")), b = image::readImage(path("ref.exr"));
  // Over the plane's pixels (the background is black): both Monte Carlo at 256 samples, so
  // they agree to a fraction of a percent; a wrong vertex order or scale is far off.
  double sum = 0, sq = 0;
  std::size_t hits = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (a.pixels[i].x > 0) {
      sum += a.pixels[i].x;
      sq += double(a.pixels[i].x - b.pixels[i].x) * double(a.pixels[i].x - b.pixels[i].x);
      ++hits;
    }
  ASSERT_GT(hits, 200u);
  EXPECT_LT(std::sqrt(sq / double(hits)), 0.01 * sum / double(hits));
  Json j = Json::parse(slurp(dir_ / "ref.json"));
  for (auto& c : j["radiance"])
    for (auto& v : c) v = v.get<double>() * 2;
  write("ref.json", formatJson(j));
  // The fingerprints still match (the radiance is not part of them): the file is drawn as it is.
  ASSERT_EQ(prt("-q render p.glb --reference ref.json -o ref2.exr" + view).rc, 0);
  const image::Image c = image::readImage(path("ref2.exr"));
  double sa = 0, sc = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) sa += a.pixels[i].x, sc += c.pixels[i].x;
  ASSERT_GT(sa, 0);
  EXPECT_NEAR(sc / sa, 2.0, 1e-3);
  // An image needs every vertex.
  ASSERT_EQ(prt("-q reference p.glb --light builtin:constant --samples 4 --vertices 10 -o "
                "part.json").rc,
            0);
  expectCleanFailure("render p.glb --light builtin:constant --reference part.json -o out/x.png",
                     "covers 10 of the mesh's");
}

}  // namespace
}  // namespace prt::testing
