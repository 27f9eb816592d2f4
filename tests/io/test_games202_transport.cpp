// transport.txt: the course's face layout and our vertex layout, the OBJ vertex order the course
// relies on (checked against the OBJ text itself, not against our loader's idea of it), exact
// float round trip, and rejection of malformed files.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

#include "common/random_data.hpp"
#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/io/games202_transport.hpp"

namespace prt {
namespace {

// Positions shared between faces with different normals and texture coordinates: the course's
// loader makes one vertex per distinct v/vt/vn triple, in order of first appearance.
const char* kObj = R"(# test
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
vn 0 0 -1
vn 1 0 0
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
f 1/1/2 3/3/2 2/2/2
f 2/1/3 3/4/3 5/2/3
)";

struct ObjText {
  std::vector<std::array<float, 3>> v, vn;
  std::vector<std::array<float, 2>> vt;
  std::vector<std::array<int, 3>> corners;  // (v, vt, vn) 0-based, per face corner in order
};
ObjText parseObjText(const std::string& text) {
  ObjText o;
  std::istringstream in(text);
  std::string tag;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    ls >> tag;
    if (tag == "v" || tag == "vn") {
      std::array<float, 3> p;
      ls >> p[0] >> p[1] >> p[2];
      (tag == "v" ? o.v : o.vn).push_back(p);
    } else if (tag == "vt") {
      std::array<float, 2> t;
      ls >> t[0] >> t[1];
      o.vt.push_back(t);
    } else if (tag == "f") {
      for (std::string c; ls >> c;) {
        int a, b, n;
        EXPECT_EQ(std::sscanf(c.c_str(), "%d/%d/%d", &a, &b, &n), 3) << c;
        o.corners.push_back({a - 1, b - 1, n - 1});
      }
    }
  }
  return o;
}

// A transfer that names its vertex: (position, uv, normal, index) — 9 numbers = 3 bands.
Transfer selfDescribing(const Mesh& m) {
  std::vector<float> values(m.vertexCount() * 9);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    float* r = values.data() + 9 * v;
    r[0] = m.positions[v].x, r[1] = m.positions[v].y, r[2] = m.positions[v].z;
    r[3] = m.uvs.empty() ? -1 : m.uvs[v].x, r[4] = m.uvs.empty() ? -1 : m.uvs[v].y;
    r[5] = m.normals[v].x, r[6] = m.normals[v].y, r[7] = m.normals[v].z;
    r[8] = static_cast<float>(v);
  }
  return testdata::denseTransfer(TransferLayout::Vector, 3, 1, std::move(values));
}

// Does a 9-number row describe the OBJ triple (v, vt, vn)?
bool rowIsTriple(const float* r, const ObjText& o, const std::array<int, 3>& c) {
  const auto& p = o.v[c[0]];
  const auto& t = o.vt[c[1]];
  const auto& n = o.vn[c[2]];
  const bool uvOk = r[3] == t[0] && (r[4] == t[1] || r[4] == 1.0f - t[1]);  // either v convention
  return r[0] == p[0] && r[1] == p[1] && r[2] == p[2] && uvOk && std::abs(r[5] - n[0]) < 1e-6f &&
         std::abs(r[6] - n[1]) < 1e-6f && std::abs(r[7] - n[2]) < 1e-6f;
}

class Games202Obj : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = std::make_unique<prt::testing::ScratchDir>();
    dir_ = scratch_->path();
    obj_ = (dir_ / "shared.obj").string();
    std::ofstream(obj_) << kObj;
  }
  void TearDown() override { scratch_.reset(); }
  std::unique_ptr<prt::testing::ScratchDir> scratch_;  // this test's own folder (ctest -j)
  std::filesystem::path dir_;
  std::string obj_;
};

TEST_F(Games202Obj, FaceLayoutFollowsTheCourseVertexOrder) {
  const ObjText o = parseObjText(kObj);
  // The course's vertex list, derived from the text: distinct triples in first-appearance order.
  std::map<std::array<int, 3>, int> id;
  std::vector<std::array<int, 3>> order;
  for (const auto& c : o.corners)
    if (id.emplace(c, static_cast<int>(order.size())).second) order.push_back(c);
  ASSERT_EQ(order.size(), 10u);  // 5 positions become 10 vertices

  const Mesh mesh = loadMesh(obj_);
  ASSERT_EQ(mesh.vertexCount(), order.size());
  ASSERT_EQ(mesh.triangleCount(), o.corners.size() / 3);
  const Transfer f = selfDescribing(mesh);

  // Faces (the course's file): header V, then one line per face corner.
  const Games202Transport faces =
      parseGames202Transport(formatGames202Transport(f, mesh), "faces.txt");
  EXPECT_EQ(faces.vertexCount, order.size());
  EXPECT_EQ(faces.layout, Games202Layout::Faces);
  EXPECT_EQ(faces.bands, 3);
  ASSERT_EQ(faces.rowCount, o.corners.size());
  for (std::size_t k = 0; k < o.corners.size(); ++k) {
    const float* r = faces.rows.data() + k * 9;
    EXPECT_TRUE(rowIsTriple(r, o, o.corners[k])) << "corner " << k;
    EXPECT_EQ(r[8], static_cast<float>(id[o.corners[k]])) << "corner " << k << " vertex index";
  }
  // Vertices: line v is the v-th distinct triple.
  const Games202Transport verts = parseGames202Transport(
      formatGames202Transport(f, mesh, Games202Layout::Vertices), "verts.txt");
  EXPECT_EQ(verts.layout, Games202Layout::Vertices);
  ASSERT_EQ(verts.rowCount, order.size());
  for (std::size_t v = 0; v < order.size(); ++v)
    EXPECT_TRUE(rowIsTriple(verts.rows.data() + v * 9, o, order[v])) << "vertex " << v;
}

TEST_F(Games202Obj, ExactTextLayoutAndFloatRoundTrip) {
  const Mesh mesh = loadMesh(obj_);
  std::vector<float> values;  // any band count: B² numbers per line
  for (std::size_t i = 0; i < mesh.vertexCount() * 4; ++i)
    values.push_back(std::nextafter(1.0f / float(i + 3), 1.0f) * (i % 2 ? -1.0f : 1.0f));
  const Transfer f = testdata::denseTransfer(TransferLayout::Vector, 2, 1, values);
  const std::string text = formatGames202Transport(f, mesh, Games202Layout::Vertices);
  // First line, then "x x x x \n": each number followed by a space, as the course writes.
  EXPECT_EQ(text.substr(0, 3), "10\n");
  const std::string line1 = text.substr(3, text.find('\n', 3) - 3);
  EXPECT_EQ(line1.back(), ' ');
  EXPECT_EQ(std::count(line1.begin(), line1.end(), ' '), 4);
  const std::string path = (dir_ / "t.txt").string();
  writeGames202Transport(path, f, mesh, Games202Layout::Vertices);
  const Games202Transport t = readGames202Transport(path);
  EXPECT_EQ(t.bands, 2);
  ASSERT_EQ(t.rows.size(), values.size());
  EXPECT_EQ(std::memcmp(t.rows.data(), values.data(), values.size() * 4), 0);
}

TEST(Games202Transport, RgbNeedsAChannel) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals.assign(3, {0, 0, 1});
  m.triangles = {{0, 1, 2}};
  const Transfer rgb =
      testdata::denseTransfer(TransferLayout::Vector, 1, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  EXPECT_THROW(formatGames202Transport(rgb, m), Error);
  const Transfer lum = selectChannel(rgb, ChannelSelect::Luminance);
  EXPECT_EQ(lum.channels(), 1);
  EXPECT_FLOAT_EQ(lum.values()[1], 0.2126f * 4 + 0.7152f * 5 + 0.0722f * 6);
  EXPECT_EQ(selectChannel(rgb, ChannelSelect::Blue).values()[2], 9.0f);
  EXPECT_EQ(selectChannel(rgb, ChannelSelect::Red).values()[0], 1.0f);
  EXPECT_EQ(parseChannelSelect("g"), ChannelSelect::Green);
  EXPECT_THROW(parseChannelSelect("alpha"), Error);
  // A field that does not cover the mesh is refused.
  const Transfer small = testdata::denseTransfer(TransferLayout::Vector, 1, 1, {1, 2});
  EXPECT_THROW(formatGames202Transport(small, m), Error);
  // Matrices are never written as if a row of them were a vector (issue: row 0 exported).
  const Transfer matrices = testdata::denseTransfer(TransferLayout::Matrix, 1, 1, {1, 2, 3});
  try {
    formatGames202Transport(matrices, m);
    FAIL() << "matrices were written as vectors";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("matrix"), std::string::npos) << e.what();
  }
}

TEST(Games202Transport, MalformedFilesAreRejected) {
  auto bad = [](const std::string& text) {
    EXPECT_THROW(parseGames202Transport(text, "bad.txt"), Error) << text;
  };
  bad("");
  bad("abc\n1 2 3 4\n");
  bad("-3\n1\n1\n1\n");
  bad("2\n");                      // no rows
  bad("2\n1 2 3\n1 2 3\n");        // 3 is not a square
  bad("2\n1 2 3 4\n1 2 3\n");      // ragged
  bad("2\n1 2 x 4\n1 2 3 4\n");    // not a number
  bad("2\n1 2 nan 4\n1 2 3 4\n");  // non-finite
  bad("4\n1\n2\n3\n4\n5\n");       // 5 lines: neither 4 vertices nor faces
  try {
    parseGames202Transport("2\n1 2 3 4\n1 2 3\n", "r.txt");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("r.txt:3"), std::string::npos) << e.what();
  }
  // Good ones: both layouts, with or without the trailing spaces, CRLF line ends.
  const auto v = parseGames202Transport("2\r\n1 2 3 4\r\n5 6 7 8\r\n", "ok.txt");
  EXPECT_EQ(v.layout, Games202Layout::Vertices);
  EXPECT_EQ(v.rows.back(), 8.0f);
  const auto f = parseGames202Transport("1\n1 \n1 \n1 \n", "ok.txt");
  EXPECT_EQ(f.layout, Games202Layout::Faces);
  EXPECT_EQ(f.bands, 1);
}

}  // namespace
}  // namespace prt
