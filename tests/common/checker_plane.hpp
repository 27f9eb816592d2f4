#pragma once
// A textured low-poly asset for the viewers' tests (issue 18: the base-colour texture per
// pixel): a 4 × 4 square of two triangles whose map_Kd is a 16 × 16 checker of 4-texel red and
// blue squares, repeated twice across it (vt 0..2: repeat wrapping). Four vertices cannot carry
// the checker — folding the texture at the vertices gives one flat blend — so an image that
// shows it multiplied the texture per pixel. `plain` writes the same square without the texture
// (the control).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "prt/image/image_io.hpp"

namespace prt::testing {

/// Writes DIR/checker.obj (textured) or DIR/checker-plain.obj (`plain`), with its .mtl and PNG;
/// returns the OBJ's path.
inline std::string writeCheckerPlane(const std::filesystem::path& dir, bool plain = false) {
  image::Srgb8Image tex;
  tex.width = tex.height = 16;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool red = ((x / 4) + (y / 4)) % 2 != 0;
      tex.rgb.insert(tex.rgb.end(), {std::uint8_t(red ? 230 : 40), std::uint8_t(red ? 60 : 120),
                                     std::uint8_t(red ? 40 : 230)});
    }
  const std::string name = plain ? "checker-plain" : "checker";
  std::ofstream(dir / "checker.png", std::ios::binary) << image::encodePng(tex, "checker.png");
  std::ofstream(dir / (name + ".mtl"))
      << "newmtl m\nKd 1 1 1\n" << (plain ? "" : "map_Kd checker.png\n");
  std::ofstream(dir / (name + ".obj"))
      << "mtllib " << name << ".mtl\nv -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n"
      << "vt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nvn 0 1 0\nusemtl m\nf 1/1/1 4/4/1 3/3/1 2/2/1\n";
  return (dir / (name + ".obj")).string();
}

}  // namespace prt::testing
