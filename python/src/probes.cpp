// Probe grids from Python (issue 32): bake_probes (prt probes), relight_probes (the light
// arriving at every probe under a light, as numpy) and shade_probes (a moving object's normals
// shaded from the grid). The library does the work: transport's one bake over the probe domain,
// relight/relight_probes.hpp.

#include <array>
#include <optional>

#include "common.hpp"
#include "objects.hpp"
#include "prt/core/error.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/transport/bake_request.hpp"
#include "prt/transport/passes.hpp"

namespace prtpy {

namespace {

std::array<int, 3> gridCounts(py::handle grid) {
  if (py::isinstance<py::str>(grid)) {
    if (grid.cast<std::string>() == "auto") return {0, 0, 0};
    throw py::value_error("grid must be 'auto' or (nx, ny, nz)");
  }
  const auto t = grid.cast<std::vector<long long>>();
  if (t.size() != 3) throw py::value_error("grid must be 'auto' or (nx, ny, nz)");
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) {
    if (t[a] < 1 || t[a] > prt::kMaxProbeSide)
      throw py::value_error("grid: each count must lie in 1.." +
                            std::to_string(prt::kMaxProbeSide));
    n[a] = int(t[a]);
  }
  return n;
}

std::optional<std::pair<prt::Vec3f, prt::Vec3f>> gridBounds(py::handle bounds) {
  if (bounds.is_none()) return std::nullopt;
  const auto b = floats(bounds, "bounds", {2, 3});
  const float* v = b.data();
  return std::make_pair(prt::Vec3f(v[0], v[1], v[2]), prt::Vec3f(v[3], v[4], v[5]));
}

}  // namespace

void bindProbes(py::module_& m) {
  m.def(
      "bake_probes",
      [](py::object meshObj, py::object grid, py::object bounds, const std::string& mode,
         int bands, long long samples, std::uint64_t seed, int bounces, py::object albedo,
         py::object range, py::object progress) {
        const MeshPtr mesh = toMesh(meshObj);
        prt::BakeRequest r;
        asValueError([&] {
          r.modes = {prt::parseTransferMode(mode)};
          return 0;
        });
        r.layout = prt::TransferLayout::Matrix;
        r.domain = prt::TransferDomain::Probes;
        r.bands = bands;
        r.samples = samples;
        r.bounces = bounces;
        r.seed = seed;
        r.probes.count = gridCounts(grid);
        r.probes.bounds = gridBounds(bounds);
        if (!albedo.is_none()) r.albedo = rgb(albedo, "albedo");
        prt::Mesh prepared = mesh->mesh();
        const prt::BakeSettings s = asValueError([&] {
          prt::checkBakeRequest(r, prt::OptionSpelling::Python);
          prt::prepareBakeMesh(prepared, r);
          return prt::bakeSettings(r, prepared, r.modes[0]);
        });
        r.rows = rowRange(range, s.probes.probes(), "probe");
        auto t = std::make_shared<PyTransfer>();
        t->recipe = s;
        prt::BakeStats stats;
        t->transfer = runLong("bake probes", progress, [&](const prt::ProgressFn& fn) {
          prt::ThreadExecutor threads;
          prt::BakeObserver observer;
          observer.progress = [&](const prt::BakeSettings&) { return fn; };
          std::vector<prt::BakeResult> results =
              prt::bake(r, prepared, mesh->occluder(), threads, observer);
          stats = results[0].stats;
          return std::move(results[0].transfer);
        });
        t->stats = stats;
        return t;
      },
      py::arg("mesh"), py::arg("grid") = "auto", py::arg("bounds") = py::none(),
      py::arg("mode") = "interreflected", py::arg("bands") = 3, py::arg("samples") = 1024,
      py::arg("seed") = 0, py::arg("bounces") = 1, py::arg("albedo") = py::none(),
      py::arg("range") = py::none(), py::arg("progress") = py::none(),
      R"(Bakes relightable probes (prt probes): at each probe of a grid in the scene, the B² x B²
matrix M from the distant light's SH L to the SH of the light arriving there, M L, shadowed by
the scene and with the light its surfaces bounce (mode 'interreflected', bounces, their albedo).
grid: 'auto' (16 cells along the longest side of the bounds) or (nx, ny, nz); a probe at each
    cell's centre, probe (x, y, z) row x + nx*(y + ny*z).
bounds: ((x0, y0, z0), (x1, y1, z1)), the box the grid fills; None: the mesh's bounds.
Returns a prtkit.Transfer over the domain 'probes' (its .probe_grid says where they are),
bit-identical to prt probes with the same settings; write_bake writes it.)");

  m.def(
      "relight_probes",
      [](py::handle transferObj, py::handle lightObj, py::handle rot) {
        const TransferPtr t = toTransfer(transferObj);
        prt::sh::RgbSh light = prtpy::light(lightObj);
        if (!rot.is_none()) {
          const prt::sh::Rotation r(light.bands, rotation(rot));
          prt::sh::RgbSh turned(light.bands);
          r.apply(light.c.data(), turned.c.data());
          light = std::move(turned);
        }
        prt::relight::ProbeLighting l;
        {
          py::gil_scoped_release nogil;
          l = asValueError([&] { return prt::relight::relightProbes(t->transfer, light); });
        }
        const prt::ProbeGrid g = l.grid;
        const auto b2 = static_cast<py::ssize_t>(l.coeffs());
        std::vector<float> flat(l.coefficients.size() * 3);
        for (std::size_t i = 0; i < l.coefficients.size(); ++i)
          for (int c = 0; c < 3; ++c) flat[3 * i + std::size_t(c)] = l.coefficients[i][std::size_t(c)];
        return adoptVector(std::move(flat), {g.count[2], g.count[1], g.count[0], b2, 3});
      },
      py::arg("transfer"), py::arg("light"), py::arg("rotation") = py::none(),
      R"(The SH of the light arriving at every probe of a probe bake under `light` ((B², 3) SH,
turned by `rotation`, a 3x3 matrix, first): float32 (nz, ny, nx, B², 3), probe (x, y, z) at
[z, y, x], at min(light, transfer) bands.)");

  m.def(
      "shade_probes",
      [](py::handle transferObj, py::handle lightObj, py::handle points, py::handle normals,
         py::handle albedo) {
        const TransferPtr t = toTransfer(transferObj);
        const prt::sh::RgbSh light = prtpy::light(lightObj);
        const auto p = floats(points, "points", {kAny, 3});
        const auto n = floats(normals, "normals", {p.shape(0), 3});
        const prt::Rgb rho = albedo.is_none() ? prt::Rgb(1.0f) : rgb(albedo, "albedo");
        const std::size_t count = static_cast<std::size_t>(p.shape(0));
        std::vector<float> out(count * 3);
        {
          py::gil_scoped_release nogil;
          const prt::relight::ProbeLighting l =
              asValueError([&] { return prt::relight::relightProbes(t->transfer, light); });
          std::vector<prt::Rgb> sh(l.coeffs());
          for (std::size_t i = 0; i < count; ++i) {
            const float* q = p.data() + 3 * i;
            const float* nn = n.data() + 3 * i;
            prt::relight::sampleProbes(l, prt::Vec3f(q[0], q[1], q[2]), sh.data());
            const prt::Rgb e = prt::relight::shadeDiffuse(
                sh.data(), l.bands, prt::normalize(prt::Vec3f(nn[0], nn[1], nn[2])), rho);
            for (int c = 0; c < 3; ++c) out[3 * i + std::size_t(c)] = e[std::size_t(c)];
          }
        }
        return adoptVector(std::move(out), {static_cast<py::ssize_t>(count), 3});
      },
      py::arg("transfer"), py::arg("light"), py::arg("points"), py::arg("normals"),
      py::arg("albedo") = py::none(),
      R"(Diffuse exit radiance (N, 3) of surface points (N, 3) with normals (N, 3) of a moving object
placed in a probe bake's grid, lit by `light` through the probes (trilinear blend of the eight
around each point, then the clamped-cosine convolution): albedo * E(n) / pi.)");
}

}  // namespace prtpy
