#include "prt/haar/cube_haar.hpp"

#include <algorithm>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/envmap/layout.hpp"

namespace prt::haar {

namespace {

/// One face, level by level from the finest (the steps of the header's pyramid).
template <typename T>
void forwardFace(T* face, int n, std::vector<T>& block) {
  for (int s = n; s > 1; s /= 2) {
    const int h = s / 2;
    block.assign(face, face + std::size_t(n) * n);  // rows of n; only the top-left s×s is read
    const auto at = [&](int x, int y) { return block[std::size_t(y) * n + x]; };
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < h; ++i) {
        const T a = at(2 * i, 2 * j), b = at(2 * i + 1, 2 * j);
        const T c = at(2 * i, 2 * j + 1), d = at(2 * i + 1, 2 * j + 1);
        face[std::size_t(j) * n + i] = T(0.5) * (a + b + c + d);
        face[std::size_t(j) * n + h + i] = T(0.5) * (a - b + c - d);
        face[std::size_t(h + j) * n + i] = T(0.5) * (a + b - c - d);
        face[std::size_t(h + j) * n + h + i] = T(0.5) * (a - b - c + d);
      }
  }
}

template <typename T>
void forwardCube(T* cube, int n) {
  checkResolution(n, "Haar transform");
  std::vector<T> block;
  for (int f = 0; f < 6; ++f) forwardFace(cube + std::size_t(f) * n * n, n, block);
}

}  // namespace

void checkResolution(int resolution, const std::string& what) {
  if (!validResolution(resolution))
    throw Error(what + ": the cube's resolution must be a power of two from " +
                std::to_string(kMinResolution) + " to " + std::to_string(kMaxResolution) +
                ", got " + std::to_string(resolution));
}

void forward(float* cube, int resolution) {
  forwardCube(cube, resolution);
}
void forward(double* cube, int resolution) {
  forwardCube(cube, resolution);
}

void inverse(float* cube, int n) {
  checkResolution(n, "Haar transform");
  std::vector<float> block;
  for (int f = 0; f < 6; ++f) {
    float* face = cube + std::size_t(f) * n * n;
    for (int s = 2; s <= n; s *= 2) {
      const int h = s / 2;
      block.assign(face, face + std::size_t(n) * n);
      const auto at = [&](int x, int y) { return block[std::size_t(y) * n + x]; };
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < h; ++i) {
          const float avg = at(i, j), dh = at(h + i, j), dv = at(i, h + j), dd = at(h + i, h + j);
          face[std::size_t(2 * j) * n + 2 * i] = 0.5f * (avg + dh + dv + dd);
          face[std::size_t(2 * j) * n + 2 * i + 1] = 0.5f * (avg - dh + dv - dd);
          face[std::size_t(2 * j + 1) * n + 2 * i] = 0.5f * (avg + dh - dv - dd);
          face[std::size_t(2 * j + 1) * n + 2 * i + 1] = 0.5f * (avg - dh - dv + dd);
        }
    }
  }
}

CubeTexel cubeTexel(std::uint32_t index, int n) {
  const std::uint32_t face = std::uint32_t(n) * std::uint32_t(n);
  const std::uint32_t f = index / face, r = index % face;
  return {int(f), int(r % std::uint32_t(n)), int(r / std::uint32_t(n))};
}

std::uint32_t texelOf(const Vec3f& direction, int n) {
  float s = 0, t = 0;
  const int f = envmap::cubeFaceCoords(direction, s, t);
  const int x = std::clamp(int((s + 1.0f) * 0.5f * float(n)), 0, n - 1);
  const int y = std::clamp(int((t + 1.0f) * 0.5f * float(n)), 0, n - 1);
  return std::uint32_t(f) * std::uint32_t(n) * std::uint32_t(n) + std::uint32_t(y) * n +
         std::uint32_t(x);
}

}  // namespace prt::haar
