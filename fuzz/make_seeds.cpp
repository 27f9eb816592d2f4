// Writes a small seed corpus for every fuzz target: OUT/<target>/<name>. The images, lights,
// transport text and bakes come from our own writers (so they are exactly what prtkit produces,
// and follow the formats as they evolve); meshes and material specs are tiny hand-written inputs
// covering each variant the readers accept. The bakes cover every representation the bake
// reader decodes — dense vectors, dense matrices, CPCA-compressed vectors and matrices — as the
// writer writes them today (format version 4); the files of versions 1–3 (spec-string
// materials, the separate albedo) are in fuzz/corpus/bake/ as accept_v*.glb, copies of
// tests/data/bakes/. Run at build time for the replay tests (fuzz/CMakeLists.txt) and by
// scripts/fuzz.sh.
//
//   make_seeds OUT

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <stb_image_write.h>
#include <zlib.h>

#include "prt/compress/cpca.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/io/reference_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"

namespace fs = std::filesystem;

namespace {

fs::path gOut;

void put(const std::string& target, const std::string& name, const std::string& bytes) {
  fs::create_directories(gOut / target);
  std::ofstream(gOut / target / name, std::ios::binary) << bytes;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string gzip(const std::string& s) {
  z_stream zs{};
  deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&zs, s.size()) + 32, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(s.data()));
  zs.avail_in = static_cast<uInt>(s.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

const char* kTetraPly =
    "ply\nformat ascii 1.0\ncomment tetrahedron\nelement vertex 4\nproperty float x\n"
    "property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float u\n"
    "property float v\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 1 255 0 0 0 0\n1 0 0 0 0 1 0 255 0 1 0\n0 1 0 0 0 1 0 0 255 0 1\n"
    "0 0 1 0 0 1 9 9 9 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string binaryPly() {
  std::string h =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
      "y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  h.append(reinterpret_cast<const char*>(v), sizeof v);
  h.push_back(3);
  const unsigned idx[3] = {0, 1, 2};
  h.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return h;
}

// One triangle; the buffer is a base64 data URI: 3 float3 positions then 3 uint16 indices.
const char* kGltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"children":[1]},{"mesh":0,"translation":[1,0,0]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1]}}],
"buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";

/// A bake of the 12-vertex icosahedron: one transfer of `layout` at `bands`, CPCA-compressed
/// (2 clusters, 1 basis vector) when `compressed`; with a 2 × 2 base-colour texture (the one
/// image a bake holds, an embedded PNG) over planar texture UVs when `textured`.
std::string bakeSeed(prt::TransferLayout layout, int bands, bool compressed,
                     bool textured = false) {
  prt::BakeFile file;
  file.mesh = prt::builtinScene("builtin:sphere?subdiv=0");
  file.generator = "prtkit make_seeds";
  const auto occluder = prt::makeEmbreeOccluder(file.mesh);
  prt::BakeSettings s;
  s.mode = prt::TransferMode::Unshadowed;
  s.layout = layout;
  s.bands = bands;
  s.samples = 16;
  if (layout == prt::TransferLayout::Matrix)
    s.material = prt::parseMaterial("phong?exponent=8&ks=0.5");
  prt::BakedTransfer t;
  t.recipe = s;
  t.transfer = prt::bake(file.mesh, *occluder, s, &t.stats);
  if (compressed) {
    prt::CpcaOptions o;
    o.clusters = 2;
    o.basisCount = 1;
    t.compression.fit = o;
    t.transfer = prt::compressCpca(t.transfer, o, &t.compression.stats);
  }
  file.transfers.push_back(std::move(t));
  if (textured) {
    for (const prt::Vec3f& p : file.mesh.positions)
      file.mesh.uvs.push_back({0.5f + 0.5f * p.x, 0.5f - 0.5f * p.y});
    prt::BaseColourTexture tex;
    tex.name = "seed.png";
    tex.image.width = tex.image.height = 2;
    tex.image.rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
    file.mesh.baseColour = tex;
  }
  return prt::encodeBake(file);
}

/// A Haar bake (format 8: the quantised rows' four accessors) of the sphere over a plane, small:
/// a 4² cube keeping 8 terms a vertex, both kinds of row; inter-reflected (format 9), each row's
/// bounce too, in 2 SH bands, RGB, in a fifth accessor.
std::string haarBakeSeed(bool interreflected = false) {
  prt::BakeFile file;
  file.mesh = prt::builtinScene("builtin:sphere-plane?grid=4&subdiv=0");
  file.generator = "prtkit make_seeds";
  const auto occluder = prt::makeEmbreeOccluder(file.mesh);
  prt::BakeSettings s;
  s.mode = prt::TransferMode::Shadowed;
  s.basis = prt::TransferBasis::Haar;
  s.haar = {4, 8};
  s.samples = 1;
  if (interreflected) {
    s.mode = prt::TransferMode::Interreflected;
    s.bounces = 1;
    s.haar.bounceBands = 2;
    s.material.diffuse = prt::Rgb(0.8f, 0.5f, 0.2f);
  }
  prt::BakedTransfer t;
  t.recipe = s;
  t.transfer = prt::bake(file.mesh, *occluder, s, &t.stats);
  file.transfers.push_back(std::move(t));
  return prt::encodeBake(file);
}

/// A per-texel bake of the builtin plane (a 2 × 2 grid, its packed lightmap chart) at 8 × 8
/// texels: the lightmap, texel range and texel-row accessor of format 6; sampled adaptively, so
/// that its recipe holds a target error (settings.targetError).
std::string texelBakeSeed() {
  prt::BakeFile file;
  file.mesh = prt::builtinScene("builtin:plane?grid=2");
  file.generator = "prtkit make_seeds";
  const auto occluder = prt::makeEmbreeOccluder(file.mesh);
  prt::BakeSettings s;
  s.mode = prt::TransferMode::Shadowed;
  s.bands = 2;
  s.samples = 8;
  s.targetError = 0.05;
  prt::BakedTransfer t;
  t.recipe = s;
  t.transfer =
      prt::bakeTexels(file.mesh, *occluder, s, file.mesh.lightmapUvs, 8, 8, 1, &t.stats).transfer;
  file.transfers.push_back(std::move(t));
  return prt::encodeBake(file);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds OUT\n");
    return 2;
  }
  gOut = argv[1];
  fs::create_directories(gOut);
  const fs::path tmp = gOut / "tmp";
  fs::create_directories(tmp);

  // Images: an 8x4 gradient (RLE needs width >= 8) in every format we read.
  prt::image::Image img(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) img.at(x, y) = {x / 8.0f, y / 4.0f, 0.25f};
  for (const char* ext : {"hdr", "exr", "png"}) {
    const fs::path p = tmp / (std::string("img.") + ext);
    prt::image::writeImage(p.string(), img);
    put(ext == std::string("png") ? "ldr" : ext, std::string("gradient.") + ext, slurp(p));
  }
  // A JPEG of the same gradient, written by stb (prtkit itself writes no JPEGs).
  {
    unsigned char rgb[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; ++i) rgb[i] = static_cast<unsigned char>(i * 7);
    std::string jpg;
    stbi_write_jpg_to_func(
        [](void* ctx, void* data, int n) {
          static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), n);
        },
        &jpg, 8, 4, 3, rgb, 90);
    put("ldr", "gradient.jpg", jpg);
  }

  // Meshes.
  put("ply", "tetra_ascii.ply", kTetraPly);
  put("ply", "triangle_binary.ply", binaryPly());
  put("ply", "tetra.ply.gz", gzip(kTetraPly));
  const std::string off =
      "OFF\n# tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n4 1 2 3 "
      "0\n";
  put("off", "tetra.off", off);
  put("off", "tetra.off.gz", gzip(off));
  put("off", "colours.off",
      "CNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0\n1 0 0 0 0 1 0.5 0.5 0.5 1\n0 1 0 0 0 1 0 0 255\n"
      "3 0 1 2 255 255 255\n");
  put("obj", "quad.obj",
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -4 -2 -1\n"
      "\n#MTL\nnewmtl red\nKd 0.5 0.25 0.125\nmap_Kd tex.png\n");
  put("obj", "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  put("gltf", "triangle.gltf", kGltf);

  // Lights and transport.
  prt::io::LightFile light;
  light.coefficients = prt::sh::RgbSh(3);
  for (std::size_t i = 0; i < light.coefficients.c.size(); ++i)
    light.coefficients.c[i] = {0.1f * i, 0.2f, -0.05f * i};
  light.source = "seed";
  prt::io::writeLightJson((tmp / "light.json").string(), light);
  put("light_json", "light.json", slurp(tmp / "light.json"));
  prt::io::writeLightGames202((tmp / "light.txt").string(), light.coefficients);
  put("light_txt", "light.txt", slurp(tmp / "light.txt"));
  prt::io::HaarLightFile haarLight;
  haarLight.light =
      prt::haar::projectLight(prt::envmap::builtinEnvironment("builtin:sky", 64), 4, 12);
  haarLight.source = "builtin:sky";
  prt::io::writeHaarLightJson((tmp / "haar.json").string(), haarLight);
  put("haar_light_json", "haar.json", slurp(tmp / "haar.json"));
  put("light_json", "haar.json", slurp(tmp / "haar.json"));  // refused by name, not read
  prt::io::ReferenceFile ref;
  ref.bakeFile = "seed.glb";
  ref.meshVertices = 4;
  ref.meshFingerprint = "0123456789abcdef";
  ref.lightSource = "builtin:sky";
  ref.environmentFingerprint = "fedcba9876543210";
  ref.mode = "shadowed";
  ref.material = "lambert?kd=0.8";
  ref.eye = prt::Vec3f(0, 1, 3);
  ref.samples = 16;
  ref.mis = "power";
  ref.vertices = {0, 2, 3};
  ref.radiance = {prt::Rgb(0.5f), prt::Rgb(0.25f, 0.5f, 1.0f), prt::Rgb(0.0f)};
  ref.stdError = {prt::Rgb(0.01f), prt::Rgb(0.02f), prt::Rgb(0.0f)};
  prt::io::writeReferenceJson((tmp / "reference.json").string(), ref);
  put("reference_json", "reference.json", slurp(tmp / "reference.json"));
  ref.lightmapWidth = 4;  // a per-texel reference: rows are texels of a 4 x 4 lightmap
  ref.lightmapHeight = 4;
  ref.lightmapUvFingerprint = "00112233445566aa";
  ref.vertices = {1, 5, 15};
  prt::io::writeReferenceJson((tmp / "reference-texels.json").string(), ref);
  put("reference_json", "reference-texels.json", slurp(tmp / "reference-texels.json"));
  put("transport_txt", "vertices.txt", "2\n1 0.5 0 0\n0.25 0 0 1e-3\n");
  put("transport_txt", "faces.txt", "1\n1 0 0 0\n1 0 0 0\n1 0 0 0\n");

  // Bakes in every representation; the vector one is a glTF seed too (any viewer opens a bake).
  put("bake", "vector.glb", bakeSeed(prt::TransferLayout::Vector, 3, false));
  put("bake", "matrix.glb", bakeSeed(prt::TransferLayout::Matrix, 2, false));
  put("bake", "compressed_vector.glb", bakeSeed(prt::TransferLayout::Vector, 3, true));
  put("bake", "compressed_matrix.glb", bakeSeed(prt::TransferLayout::Matrix, 2, true));
  put("bake", "texels.glb", texelBakeSeed());
  put("bake", "haar.glb", haarBakeSeed());
  put("bake", "haar-interreflected.glb", haarBakeSeed(true));
  put("gltf", "bake.glb", bakeSeed(prt::TransferLayout::Vector, 2, false));
  // A base-colour texture: the bake reader's and the glTF loader's image paths.
  put("bake", "textured.glb", bakeSeed(prt::TransferLayout::Vector, 2, false, true));
  put("gltf", "textured.glb", bakeSeed(prt::TransferLayout::Vector, 2, false, true));

  // --material spec strings: every lobe, every key.
  put("material", "lambert.txt", "lambert");
  put("material", "lambert_kd.txt", "lambert?kd=0.5,0.25,0.125");
  put("material", "phong.txt", "phong?exponent=32&ks=0.5");
  put("material", "phong_kd.txt", "phong?exponent=8&ks=0.2,0.3,0.4&kd=0.4");
  put("material", "ggx.txt", "ggx?roughness=0.3&ks=0.04&kd=0.8,0.8,0.8");
  fs::remove_all(tmp);
  return 0;
}
