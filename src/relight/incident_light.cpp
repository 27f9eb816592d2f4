// The light arriving at each row of a matrix transfer, L'_p = M_p L (incident_light.hpp).

#include "prt/relight/incident_light.hpp"

#include <algorithm>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/rotate.hpp"

namespace prt::relight {

std::vector<Rgb> incidentLight(const Transfer& t, const sh::RgbSh& light, int bands,
                               const Mat3d& rotation, RelightInfo* info) {
  if (!t.isMatrix())
    throw Error(
        "incident light: the transfer holds vectors (diffuse transfer, already "
        "integrated against the normal); it needs matrices");
  if (bands < 1 || bands > t.bands())
    throw Error("incident light: " + std::to_string(bands) + " bands asked of a " +
                std::to_string(t.bands()) + "-band transfer");
  sh::checkBands(light.bands);
  const sh::Rotation rot(std::min(light.bands, t.bands()), rotation);
  const PreparedLight lit = prepareLight(light, t.bands(), &rot, info);
  const std::size_t B2 = std::size_t(t.coeffs()), n = std::size_t(bands) * std::size_t(bands);
  const std::size_t used = std::size_t(lit.bands) * std::size_t(lit.bands);
  const std::size_t C = std::size_t(t.channels()), rows = t.rowCount();
  std::vector<Rgb> out(rows * n, Rgb(0.0f));
  const bool dense = !t.compressed();
  parallelFor(rows, 64, [&](std::size_t begin, std::size_t end) {
    std::vector<float> buffer(dense ? 0 : t.stride());
    for (std::size_t r = begin; r < end; ++r) {
      const float* m =
          t.compressed() ? (t.reconstructRow(r, buffer.data()), buffer.data()) : t.row(r);
      Rgb* dst = out.data() + r * n;
      for (std::size_t i = 0; i < n; ++i) {
        // Summed in double, in the fixed order j = 0.., so the result is the same everywhere.
        double acc[3] = {0, 0, 0};
        const float* rowI = m + i * B2 * C;
        for (std::size_t j = 0; j < used; ++j)
          for (std::size_t c = 0; c < 3; ++c)
            acc[c] += double(rowI[j * C + (C == 1 ? 0 : c)]) * double(lit.interleaved[3 * j + c]);
        dst[i] = Rgb(float(acc[0]), float(acc[1]), float(acc[2]));
      }
    }
  });
  return out;
}

}  // namespace prt::relight
