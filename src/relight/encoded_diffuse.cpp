// Diffuse exit radiance through an irradiance encoding (encoded_diffuse.hpp).

#include "prt/relight/encoded_diffuse.hpp"

#include <algorithm>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/relight/incident_light.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/transfer/albedo.hpp"

namespace prt::relight {

std::vector<Rgb> encodedDiffuse(const Transfer& matrices, const sh::RgbSh& light,
                                sh::IrradianceEncoding encoding, const Material& material,
                                const Surface& surface, const Mat3d& rotation, RelightInfo* info) {
  const char* what = "encoded irradiance";
  if (material.glossy())
    throw Error(what,
                "the material " + material.spec() +
                    " has a glossy lobe; an irradiance encoding shades the diffuse part only");
  const std::size_t rows = matrices.rowCount();
  if (surface.normals.size() != rows)
    throw Error(what, std::to_string(surface.normals.size()) + " normals for " +
                          std::to_string(rows) + " rows");
  const Albedo kd(material.diffuseOr(surface.albedo), rows, what);
  // Bands 0..2 of L'_p: all any encoding reads (encodeIrradiance ignores the rest).
  const int bands = std::min(3, matrices.bands());
  const std::vector<Rgb> incident = incidentLight(matrices, light, bands, rotation, info);
  const std::size_t n = std::size_t(bands) * std::size_t(bands);
  std::vector<Rgb> out(rows);
  parallelFor(rows, 64, [&](std::size_t begin, std::size_t end) {
    sh::RgbSh received(bands);
    for (std::size_t r = begin; r < end; ++r) {
      std::copy_n(incident.data() + r * n, n, received.c.begin());
      const sh::EncodedIrradiance e = sh::encodeIrradiance(received, encoding);
      const Rgbd irradiance = sh::evaluate(e, Vec3d(surface.normals[r]));
      out[r] = kd.at(r) * Rgb(irradiance * (1.0 / kPi));
    }
  });
  return out;
}

}  // namespace prt::relight
