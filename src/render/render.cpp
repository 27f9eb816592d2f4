#include "prt/render/render.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/image/color.hpp"
#include "prt/sh/rotate.hpp"

namespace prt::render {

Background parseBackground(const std::string& spec, Rgb* colour) {
  if (spec == "env") return Background::Env;
  if (spec == "sh") return Background::Sh;
  if (spec == "none") return Background::None;
  Rgb c;
  if (spec.size() == 7 && spec[0] == '#') {
    unsigned v = 0;
    std::istringstream in(spec.substr(1));
    if (in >> std::hex >> v && (in >> std::ws).eof()) {
      c = Rgb(image::srgb8ToLinear(std::uint8_t(v >> 16)),
              image::srgb8ToLinear(std::uint8_t(v >> 8)), image::srgb8ToLinear(std::uint8_t(v)));
      if (colour) *colour = c;
      return Background::Colour;
    }
  } else {
    char c1 = 0, c2 = 0;
    std::istringstream in(spec);
    if (in >> c.x >> c1 >> c.y >> c2 >> c.z && c1 == ',' && c2 == ',' && (in >> std::ws).eof() &&
        isFinite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0) {
      if (colour) *colour = c;
      return Background::Colour;
    }
  }
  throw Error("background '" + spec +
              "' is not env, sh, none, a linear colour r,g,b or an sRGB colour #rrggbb");
}

BackgroundFn environmentBackground(const envmap::Environment& env, const Mat3d& rotation) {
  const Mat3f rt = rotation.transposed().cast<float>();
  return [&env, rt](const Vec3f& d) { return env.lookup(normalize(rt * d)); };
}

BackgroundFn shBackground(const sh::RgbSh& light, const Mat3d& rotation) {
  sh::RgbSh rotated = light;
  if (light.bands > 0) rotated = sh::Rotation(light.bands, rotation).apply(light);
  return [rotated](const Vec3f& d) { return max(sh::reconstruct(rotated, d), Rgb(0.0f)); };
}

BackgroundFn colourBackground(const Rgb& colour) {
  return [colour](const Vec3f&) { return colour; };
}

BackgroundFn background(Background kind, const Rgb& colour, const envmap::Environment* env,
                        const sh::RgbSh* light, const Mat3d& rotation) {
  switch (kind) {
    case Background::Env:
      if (env) return environmentBackground(*env, rotation);
      if (!light) throw Error("the env background needs an environment (or an SH light)");
      return shBackground(*light, rotation);  // a light file has no image
    case Background::Sh:
      if (!light) throw Error("the sh background needs an SH light");
      return shBackground(*light, rotation);
    case Background::Colour:
      return colourBackground(colour);
    case Background::None:
      break;
  }
  return {};
}

void checkFiniteRadiance(std::span<const Rgb> radiance, const std::string& label,
                         const std::string& row) {
  for (std::size_t v = 0; v < radiance.size(); ++v)
    if (!isFinite(radiance[v]))
      throw Error(label, "the relit radiance at " + row + " " + std::to_string(v) +
                             " is not finite (the transfer times the light overflows 32-bit "
                             "floats); nothing written");
}

ShadeFn vertexRadianceShader(const Mesh& mesh, std::span<const Rgb> radiance) {
  if (radiance.size() != mesh.vertexCount())
    throw Error("render: " + std::to_string(radiance.size()) + " radiance values for a mesh of " +
                std::to_string(mesh.vertexCount()) + " vertices");
  return [&mesh, radiance](const Ray&, const Hit& h) {
    const auto& t = mesh.triangles[h.triangle];
    return radiance[t[0]] * (1.0f - h.u - h.v) + radiance[t[1]] * h.u + radiance[t[2]] * h.v;
  };
}

ShadeFn texelRadianceShader(const Mesh& mesh, std::span<const Rgb> radiance, int width, int height,
                            std::span<const Rgb> albedo) {
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error("render: per-texel radiance needs the mesh's lightmap UVs");
  if (width < 1 || height < 1 || radiance.size() != std::size_t(width) * std::size_t(height))
    throw Error("render: " + std::to_string(radiance.size()) + " radiance values for a " +
                std::to_string(width) + " x " + std::to_string(height) + " lightmap");
  if (!albedo.empty() && albedo.size() != mesh.vertexCount())
    throw Error("render: " + std::to_string(albedo.size()) + " albedo values for a mesh of " +
                std::to_string(mesh.vertexCount()) + " vertices");
  return [&mesh, radiance, width, height, albedo](const Ray&, const Hit& h) {
    const auto& t = mesh.triangles[h.triangle];
    const float w0 = 1.0f - h.u - h.v;
    const Vec2f* uv = mesh.lightmapUvs.data();
    const TexelTaps taps = bilinearTaps({uv[t[0]].x * w0 + uv[t[1]].x * h.u + uv[t[2]].x * h.v,
                                         uv[t[0]].y * w0 + uv[t[1]].y * h.u + uv[t[2]].y * h.v},
                                        width, height);
    Rgb r(0.0f);
    for (int k = 0; k < 4; ++k) r += radiance[taps.texel[k]] * taps.weight[k];
    if (!albedo.empty()) r = r * (albedo[t[0]] * w0 + albedo[t[1]] * h.u + albedo[t[2]] * h.v);
    return r;
  };
}

image::Image renderRelit(const Mesh& mesh, const Occluder& occluder, std::span<const Rgb> radiance,
                         const Camera& camera, const FrameSettings& settings,
                         const BackgroundFn& background, const ProgressFn& progress) {
  return tracePrimary(camera, settings, occluder, vertexRadianceShader(mesh, radiance), background,
                      progress);
}

image::Image contactSheet(std::span<const image::Image> frames, int columns, int gap,
                          const Rgb& gapColour) {
  if (frames.empty()) throw Error("contact sheet: no frames");
  const int w = frames[0].width, h = frames[0].height;
  for (const auto& f : frames)
    if (f.width != w || f.height != h) throw Error("contact sheet: frames differ in size");
  const int n = int(frames.size());
  if (columns <= 0) columns = int(std::ceil(std::sqrt(double(n))));
  columns = std::min(columns, n);
  const int rows = (n + columns - 1) / columns;
  gap = std::max(gap, 0);
  image::Image sheet(columns * w + (columns + 1) * gap, rows * h + (rows + 1) * gap, gapColour);
  for (int k = 0; k < n; ++k) {
    const int x0 = gap + (k % columns) * (w + gap), y0 = gap + (k / columns) * (h + gap);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) sheet.at(x0 + x, y0 + y) = frames[k].at(x, y);
  }
  return sheet;
}

}  // namespace prt::render
