// prtkit.Transfer, bake, bake_transfer and compress: the transfer in and out of numpy without
// copies, baked exactly as `prt bake` bakes it.

#include <cmath>

#include "common.hpp"
#include "objects.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_request.hpp"
#include "prt/transport/passes.hpp"
#include "prt/transport/denoise_texels.hpp"
#include "prt/transport/lightmap_seam_fix.hpp"

namespace prtpy {

Shape denseShape(const prt::TransferShape& s) {
  const auto n = static_cast<py::ssize_t>(s.rows.count);
  const auto k = static_cast<py::ssize_t>(s.coeffs());
  Shape out = s.isMatrix() ? Shape{n, k, k} : Shape{n, k};
  if (s.channels != 1) out.push_back(s.channels);
  return out;
}

namespace {

/// The shape of one row in numpy: (B²[, 3]) or (B², B²[, 3]).
Shape rowShape(const prt::TransferShape& s) {
  Shape d = denseShape(s);
  d.erase(d.begin());
  return d;
}

py::dict recipeDict(const prt::BakeRecipe& r) {
  py::dict d;
  d["mode"] = prt::toString(r.mode);
  d["samples"] = r.samples;
  d["bounces"] = r.bounces;
  d["seed"] = r.seed;
  d["sampling"] = prt::toString(r.sampling);
  d["target_error"] = r.targetError;
  d["material"] = r.material.spec();
  return d;
}

py::dict statsDict(const prt::BakeStats& s) {
  py::dict d;
  d["rays"] = s.rays;
  d["rays_per_second"] = s.raysPerSecond;
  d["seconds_total"] = s.secondsTotal;
  d["seconds_direct"] = s.secondsDirect;
  d["seconds_bounce"] = s.secondsBounce;
  d["rays_bounce"] = s.raysBounce;
  d["threads"] = s.threads;
  d["vertices"] = s.vertices;
  d["std_err_t0_mean"] = s.stdErrT0Mean;
  d["std_err_t0_max"] = s.stdErrT0Max;
  d["std_err_const_mean"] = s.stdErrConstMean;
  d["std_err_const_max"] = s.stdErrConstMax;
  d["rays_per_row_and_pass"] = s.raysPerRowAndPass();
  return d;
}

py::dict compressionDict(const prt::CpcaRecord& r) {
  py::dict fit, stats, d;
  fit["seed"] = r.fit.seed;
  fit["max_iterations"] = r.fit.maxIterations;
  fit["tolerance"] = r.fit.tolerance;
  stats["squared_error"] = r.stats.squaredError;
  stats["signal_energy"] = r.stats.signalEnergy;
  stats["relative_rms"] = r.stats.relativeRms;
  stats["snr_db"] = r.stats.snrDb;
  stats["max_row_error"] = r.stats.maxRowError;
  stats["compression_ratio"] = r.stats.compressionRatio;
  stats["seconds"] = r.stats.seconds;
  stats["iterations"] = r.stats.iterations;
  d["fit"] = fit;
  d["stats"] = stats;
  return d;
}

/// The transfer's CPCA arrays (read-only views kept alive by the Transfer object).
py::array cpcaArray(py::handle self, const prt::FloatArray& a, const Shape& shape) {
  return view(py::dtype::of<float>(), shape, a.data(), self, false);
}

/// The recipe a Transfer made from an array records, from the keywords given (None: none).
std::optional<prt::BakeRecipe> recipeOf(py::handle mode, py::handle samples, py::handle bounces,
                                        py::handle seed, py::handle sampling, py::handle spec) {
  if (mode.is_none() && samples.is_none() && bounces.is_none() && seed.is_none() &&
      sampling.is_none() && spec.is_none())
    return std::nullopt;
  prt::BakeRecipe r;
  asValueError([&] {
    if (!mode.is_none()) r.mode = prt::parseTransferMode(mode.cast<std::string>());
    if (!sampling.is_none()) {
      const auto s = sampling.cast<std::string>();
      r.sampling = prt::parseSampling(s);
    }
    return 0;
  });
  if (!samples.is_none()) r.samples = samples.cast<int>();
  if (!bounces.is_none()) r.bounces = bounces.cast<int>();
  if (!seed.is_none()) r.seed = seed.cast<std::uint64_t>();
  r.material = material(spec);
  r.bounces = r.effectiveBounces();
  return r;
}

}  // namespace

prt::RowRange rowRange(py::handle range, std::size_t vertices, const char* what) {
  if (range.is_none()) return {0, vertices};
  long long first = 0, end = 0;
  if (py::isinstance(range, py::module_::import("builtins").attr("range"))) {
    if (range.attr("step").cast<long long>() != 1) throw py::value_error("range must have step 1");
    first = range.attr("start").cast<long long>();
    end = range.attr("stop").cast<long long>();
  } else {
    const auto pair = range.cast<std::vector<long long>>();
    if (pair.size() != 2) throw py::value_error("range must be (first, end)");
    first = pair[0];
    end = pair[1];
  }
  if (first < 0 || first >= end || static_cast<unsigned long long>(end) > vertices)
    throw py::value_error("range (" + std::to_string(first) + ", " + std::to_string(end) +
                          "): must satisfy 0 <= first < end <= " + std::to_string(vertices) +
                          " (the " + what + " count)");
  return {static_cast<std::size_t>(first), static_cast<std::size_t>(end - first)};
}

namespace {

/// The request `prt bake` would make of the same options (bake_setup.cpp), checked before any
/// work by the library's one check, with Python's spelling: ValueError on a bad argument.
/// domain='texels': the lightmap.
struct Lightmap {
  int resolution = 512;
  std::string uv = "auto";
  int padding = 2;
  bool seamFix = false;  ///< the least-squares seam fix (prt bake --seam-fix)
  bool denoise = false;  ///< the à-trous filter (prt bake --denoise)
};

/// basis='haar': the cube and each row's budget of terms (prt bake --basis haar).
struct Basis {
  std::string name = "sh";
  int cubeResolution = prt::kDefaultHaarResolution;
  int terms = prt::kDefaultHaarTerms;
};

/// samples=None: the basis's default (prt bake's: 1024 directions; Haar 1 ray per cube texel).
long long samplesOf(py::handle samples, const Basis& basis) {
  if (samples.is_none())
    return asValueError([&] { return prt::defaultSamples(prt::parseTransferBasis(basis.name)); });
  return samples.cast<long long>();
}

/// A Haar transfer's rows (1 + 2K floats: kind, then K (index, value) pairs, then an
/// inter-reflected row's bounce) as numpy columns: 0 the kinds (rows,) uint8, 1 the indices
/// (rows, K) uint32, 2 the values (rows, K) float32, 3 the bounce (rows, B², C) float32.
py::array haarColumn(const PyTransfer& t, int column) {
  if (!t.transfer.isHaar())
    throw py::value_error(
        "the transfer is SH: haar_kinds, haar_indices and haar_values are a "
        "Haar transfer's (its rows are values)");
  const std::size_t rows = t.transfer.rowCount();
  const std::size_t k = static_cast<std::size_t>(t.transfer.shape().haar.terms);
  const std::size_t stride = t.transfer.stride();
  const float* v = t.transfer.values().data();
  const auto r = static_cast<py::ssize_t>(rows), kk = static_cast<py::ssize_t>(k);
  if (column == 0) {
    py::array_t<std::uint8_t> a(r);
    for (std::size_t i = 0; i < rows; ++i)
      a.mutable_data()[i] = static_cast<std::uint8_t>(v[i * stride]);
    return a;
  }
  if (column == 1) {
    py::array_t<std::uint32_t> a({r, kk});
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t j = 0; j < k; ++j)
        a.mutable_data()[i * k + j] = static_cast<std::uint32_t>(v[i * stride + 1 + 2 * j]);
    return a;
  }
  if (column == 2) {
    py::array_t<float> a({r, kk});
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t j = 0; j < k; ++j) a.mutable_data()[i * k + j] = v[i * stride + 2 + 2 * j];
    return a;
  }
  const prt::TransferShape& shape = t.transfer.shape();
  const std::size_t n = shape.haarBounceFloats(), at = shape.haarBounceOffset();
  const auto b2 = static_cast<py::ssize_t>(shape.haar.bounceBands * shape.haar.bounceBands);
  py::array_t<float> a({r, b2, static_cast<py::ssize_t>(shape.channels)});
  for (std::size_t i = 0; i < rows; ++i)
    std::copy_n(v + i * stride + at, n, a.mutable_data() + i * n);
  return a;
}

prt::BakeRequest bakeRequest(const prt::Mesh& mesh, const std::string& mode, int bands,
                             long long samples, std::uint64_t seed, int bounces,
                             const std::string& transfer, py::handle spec, py::handle albedo,
                             const std::string& sampling, py::handle range,
                             const std::string& domain, const Lightmap& lightmap,
                             double targetError, const Basis& basis) {
  prt::BakeRequest r;
  asValueError([&] {
    r.modes = {prt::parseTransferMode(mode)};
    r.basis = prt::parseTransferBasis(basis.name);
    r.layout = prt::parseTransferLayout(transfer);
    r.sampling = prt::parseSampling(sampling);
    r.domain = prt::parseTransferDomain(domain);
    r.lightmap.uv = prt::parseUvSetOption(lightmap.uv);
    return 0;
  });
  r.bands = bands;
  r.samples = samples;
  r.haar.resolution = basis.cubeResolution;
  r.haar.terms = basis.terms;
  r.bounces = bounces;
  r.seed = seed;
  r.targetError = targetError;
  if (!spec.is_none()) r.material = material(spec);
  if (!albedo.is_none()) r.albedo = rgb(albedo, "albedo");
  r.lightmap.resolution = lightmap.resolution;
  r.lightmap.padding = lightmap.padding;
  r.lightmap.seamFix = lightmap.seamFix;
  r.lightmap.denoise = lightmap.denoise;
  asValueError([&] {
    prt::checkBakeRequest(r, prt::OptionSpelling::Python);
    return 0;
  });
  r.rows = rowRange(range, prt::domainRows(mesh, prt::bakeSettings(r, mesh, r.modes[0])),
                    prt::rowName(r.domain));
  asValueError([&] {  // the seam fix against the range
    prt::checkBakeRequest(r, prt::OptionSpelling::Python);
    return 0;
  });
  return r;
}

struct Baked {
  prt::Transfer transfer;
  prt::BakeStats stats;
};

Baked runBake(py::handle meshObj, const std::string& mode, int bands, py::handle samples,
              std::uint64_t seed, int bounces, const std::string& transfer, py::handle spec,
              py::handle albedo, const std::string& sampling, py::handle range,
              const std::string& domain, const Lightmap& lightmap, double targetError,
              const Basis& basis, py::handle progress, prt::BakeSettings* used) {
  const MeshPtr mesh = toMesh(meshObj);
  const prt::BakeRequest request =
      bakeRequest(mesh->mesh(), mode, bands, samplesOf(samples, basis), seed, bounces, transfer,
                  spec, albedo, sampling, range, domain, lightmap, targetError, basis);
  // The mesh as the request bakes it (its albedo, its lightmap UV set), over the mesh's own BVH:
  // a copy, so that the Mesh object stays as the caller made it.
  prt::Mesh prepared = mesh->mesh();
  const prt::BakeMeshPreparation prep =
      asValueError([&] { return prt::prepareBakeMesh(prepared, request); });
  if (!prep.lightmapUvsFound)  // said as prt bake --uv 1|0 says it, each set's reason
    asValueError([&] {
      const int n = request.lightmap.resolution;
      return prt::chooseLightmapUvs(prepared, request.lightmap.uv, n, n).name;
    });
  if (used) *used = prt::bakeSettings(request, prepared, request.modes[0]);
  return runLong("bake", progress, [&](const prt::ProgressFn& fn) {
    prt::ThreadExecutor threads;
    prt::BakeObserver observer;
    observer.progress = [&](const prt::BakeSettings&) { return fn; };
    std::vector<prt::BakeResult> results =
        prt::bake(request, prepared, mesh->occluder(), threads, observer);
    Baked b{std::move(results[0].transfer), results[0].stats};
    if (lightmap.denoise) b.transfer = prt::denoiseTexels(prepared, mesh->occluder(), b.transfer);
    if (lightmap.seamFix) b.transfer = prt::fixLightmapSeams(prepared, b.transfer);
    return b;
  });
}

const char* kBakeArgs = R"(
mesh: a prtkit.Mesh (its BVH is kept for the next bake) or any object with .vertices and
    .faces (trimesh, Open3D: copied, BVH built each call).
mode: 'unshadowed' | 'shadowed' | 'interreflected'.
bands: SH bands B (B² coefficients; the course's SHOrder 2 is bands=3), 1..16.
samples: directions per row (None: 1024); basis='haar': rays per cube texel (None: 1);
    seed: the random seed (results never depend on threads).
bounces: inter-reflection bounces (interreflected only).
transfer: 'vector' (diffuse) | 'matrix' (glossy: B² x B² per vertex).
material: a spec ('lambert', 'phong?exponent=32&ks=0.5', 'ggx?roughness=0.3&ks=0.5', each
    with kd=r,g,b); None: the mesh file's own glossy surface, else lambert. Its kd is the
    bounce albedo; an inter-reflected matrix bake bounces light off its lobe.
albedo: a uniform bounce albedo (grey or r, g, b in [0, 1]), replacing the mesh's.
sampling: 'cosine' (cosine-weighted Owen-scrambled Sobol') | 'uniform' (the course's).
range: (first, end) or range(first, end): bake only those vertices (texels) (split bakes).
domain: 'vertices' (one row per vertex) | 'texels' (one row per texel of a resolution x
    resolution lightmap over the mesh's lightmap UVs, texel (x, y) row y*resolution + x: reshape
    to (resolution, resolution, ...) for an image; vectors and matrices).
resolution, uv, padding: domain='texels': the lightmap's side; the UV set, 'auto' (the
    lightmap set, else the texture set when it holds one), '1' or '0'; gutter texels dilated.
seam_fix: domain='texels': the least-squares seam fix (Sylvan 2015; prt bake --seam-fix):
    texels on the two sides of a UV seam agree under bilinear filtering.
denoise: domain='texels': filter the lightmap's Monte Carlo noise within each chart, before any
    seam fix (prt bake --denoise: an edge-avoiding a-trous filter of the estimated part of each
    row, transport/denoise_texels.hpp).
target_error: adaptive sampling (prt bake --target-error): 0 off; E > 0 makes samples the most a
    row casts: a pilot of 64 directions, then the power of two its standard error of radiance
    under the unit sky needs to reach E (vector SH bakes, cosine sampling; deterministic).
basis, cube_resolution, terms: 'sh' (bands) | 'haar' (prt bake --basis haar; docs/haar.md):
    all-frequency Haar wavelets over a cube of cube_resolution² texels a face (a power of two,
    2..256), each row pruned to its `terms` largest coefficients; diffuse (vector) transfer,
    per vertex or per texel (bake_transfer only: the rows are sparse terms). Inter-reflected,
    each row also holds its bounce in SH of `bands` bands (1..5; haar_bounce).
progress: None, True (a tqdm bar, when tqdm is installed) or a callable(fraction) that may
    return False to cancel (prtkit.Cancelled). Ctrl-C cancels within a fraction of a second
    (KeyboardInterrupt).
The GIL is released and all cores are used. The result is bit-identical to `prt bake` with the
same settings.)";

}  // namespace

prt::Material material(py::handle spec, const prt::Material& def) {
  if (spec.is_none()) return def;
  if (!py::isinstance<py::str>(spec))
    throw py::type_error("material must be a spec string such as 'phong?exponent=32&ks=0.5'");
  return asValueError([&] { return prt::parseMaterial(spec.cast<std::string>()); });
}

prt::Transfer transferFromArray(py::handle array, const std::optional<std::string>& layout,
                                std::size_t firstRow, bool checkFinite, const char* what) {
  const py::array a = inPlaceFloats(array, what);
  const auto d = [&](int k) { return static_cast<std::size_t>(a.shape(k)); };
  prt::TransferShape shape;
  std::size_t k = 0;
  bool ok = true;
  if (a.ndim() == 2) {
    shape.layout = prt::TransferLayout::Vector;
    k = d(1);
  } else if (a.ndim() == 3 && d(2) == 3) {
    shape.layout = prt::TransferLayout::Vector;
    shape.channels = 3;
    k = d(1);
  } else if (a.ndim() == 3) {
    shape.layout = prt::TransferLayout::Matrix;
    k = d(1);
    ok = d(2) == k;
  } else {
    shape.layout = prt::TransferLayout::Matrix;
    shape.channels = 3;
    k = d(1);
    ok = a.ndim() == 4 && d(2) == k && d(3) == 3;
  }
  const int b = static_cast<int>(std::lround(std::sqrt(static_cast<double>(k))));
  if (!ok || k == 0 || static_cast<std::size_t>(b) * static_cast<std::size_t>(b) != k)
    throw py::value_error(std::string(what) +
                          " must have shape (N, B²), (N, B², 3), (N, B², B²) or (N, B², B², 3) "
                          "with B² = 1, 4, 9, ...");
  if (layout) {
    const prt::TransferLayout want =
        asValueError([&] { return prt::parseTransferLayout(*layout); });
    if (want != shape.layout)
      throw py::value_error(std::string(what) + ": its shape is that of a " +
                            prt::toString(shape.layout) + " transfer, not a " + *layout);
  }
  if (b > prt::bands::kMaxLibrary)
    throw py::value_error(std::string(what) + " has " + std::to_string(b) + " bands (at most " +
                          std::to_string(prt::bands::kMaxLibrary) + ")");
  shape.bands = b;
  shape.rows = {firstRow, d(0)};
  if (d(0) == 0) throw py::value_error(std::string(what) + " has no rows");
  const auto* data = static_cast<const float*>(a.data());
  const std::size_t n = static_cast<std::size_t>(a.size());
  if (checkFinite) {
    bool finite = true;
    {
      py::gil_scoped_release nogil;
      for (std::size_t i = 0; i < n && finite; ++i) finite = std::isfinite(data[i]);
    }
    if (!finite) requireFinite(data, n, what, Shape(a.shape(), a.shape() + a.ndim()));
  }
  return prt::Transfer::dense(
      shape, prt::FloatArray::view(keepAlive(py::reinterpret_borrow<py::object>(a)), data, n));
}

void requireShTransfer(const PyTransfer& t, const std::string& use) {
  if (t.transfer.isHaar())
    throw py::value_error("the transfer is Haar-wavelet transfer (" +
                          t.transfer.shape().describe() + "): " + use);
}

TransferPtr toTransfer(py::handle obj, const char* what) {
  if (py::isinstance<PyTransfer>(obj)) return obj.cast<TransferPtr>();
  auto t = std::make_shared<PyTransfer>();
  t->transfer = transferFromArray(obj, std::nullopt, 0, true, what);
  return t;
}

py::array transferArray(prt::Transfer t, bool writable) {
  auto owned = std::make_unique<Owned<prt::Transfer>>(std::move(t));
  prt::Transfer& held = owned->value;
  writable = writable && !held.values().isView();
  // Storage the transfer owns alone: mutableValues() hands it out without copying.
  const float* data = writable ? held.mutableValues() : held.values().data();
  owned->data = data;
  const Shape shape = denseShape(held.shape());
  py::capsule base = capsule(std::move(owned));
  return view(py::dtype::of<float>(), shape, data, base, writable);
}

void bindTransfer(py::module_& m) {
  py::class_<PyTransfer, TransferPtr>(
      m, "Transfer",
      R"(A transfer: one row per vertex, dense or CPCA-compressed, with how it was baked.

Transfer(values, *, layout=None, first_row=0, mode=None, samples=None, bounces=None,
seed=None, sampling=None, material=None) wraps dense rows held in a numpy array, read in
place (float32, C-contiguous; shape (N, B²) or (N, B², 3) for vectors, (N, B², B²) or
(N, B², B², 3) for matrices; finite — checked once, here). The keywords record how it was
baked, for write_bake. bake_transfer, compress and read_bake_file make them too.

values is a read-only view of the dense rows (no copy); a compressed transfer exposes its
cluster_ids, weights, means and basis instead (also views) and to_dense() reconstructs it.)")
      .def(py::init([](py::object values, std::optional<std::string> layout, std::size_t firstRow,
                       py::object mode, py::object samples, py::object bounces, py::object seed,
                       py::object sampling, py::object spec) {
             auto t = std::make_shared<PyTransfer>();
             t->transfer = transferFromArray(values, layout, firstRow, true, "values");
             t->recipe = recipeOf(mode, samples, bounces, seed, sampling, spec);
             return t;
           }),
           py::arg("values"), py::kw_only(), py::arg("layout") = py::none(),
           py::arg("first_row") = 0, py::arg("mode") = py::none(), py::arg("samples") = py::none(),
           py::arg("bounces") = py::none(), py::arg("seed") = py::none(),
           py::arg("sampling") = py::none(), py::arg("material") = py::none())
      .def_property_readonly(
          "layout", [](const PyTransfer& t) { return prt::toString(t.transfer.layout()); },
          "'vector' (diffuse) or 'matrix' (glossy).")
      .def_property_readonly("domain",
                             [](const PyTransfer& t) { return prt::toString(t.transfer.domain()); })
      .def_property_readonly(
          "lightmap",
          [](const PyTransfer& t) -> py::object {
            if (t.transfer.domain() != prt::TransferDomain::Texels) return py::none();
            const auto& lm = t.transfer.shape().lightmap;
            py::dict d;
            d["width"] = lm.width;
            d["height"] = lm.height;
            d["padding"] = lm.padding;
            d["seams_fixed"] = lm.seamsFixed;
            d["denoised"] = lm.denoised;
            return py::object(std::move(d));
          },
          "domain 'texels': {'width', 'height', 'padding', 'seams_fixed', 'denoised'} of the "
          "lightmap (rows "
          "y*width + x); "
          "None per vertex.")
      .def_property_readonly(
          "probe_grid",
          [](const PyTransfer& t) -> py::object {
            if (t.transfer.domain() != prt::TransferDomain::Probes) return py::none();
            const prt::ProbeGrid& g = t.transfer.shape().probes;
            py::dict d;
            d["count"] = py::make_tuple(g.count[0], g.count[1], g.count[2]);
            d["origin"] = py::make_tuple(g.origin.x, g.origin.y, g.origin.z);
            d["spacing"] = py::make_tuple(g.spacing.x, g.spacing.y, g.spacing.z);
            return py::object(std::move(d));
          },
          "domain 'probes': {'count': (nx, ny, nz), 'origin', 'spacing'} of the grid (probe "
          "(x, y, z) at origin + (x, y, z) * spacing, row x + nx*(y + ny*z)); None otherwise.")
      .def_property_readonly(
          "bands", [](const PyTransfer& t) { return t.transfer.bands(); },
          "SH bands B (0 for Haar transfer).")
      .def_property_readonly(
          "haar",
          [](const PyTransfer& t) -> py::object {
            if (!t.transfer.isHaar()) return py::none();
            py::dict d;
            d["resolution"] = t.transfer.shape().haar.resolution;
            d["terms"] = t.transfer.shape().haar.terms;
            d["bounce_bands"] = t.transfer.shape().haar.bounceBands;
            return py::object(std::move(d));
          },
          "Haar-wavelet transfer (bake --basis haar; docs/haar.md): {'resolution': N, 'terms': "
          "K, 'bounce_bands': B} (an N² cube per face, K terms per row, an inter-reflected row's "
          "bounce in B SH bands, 0 without); None for SH transfer.")
      .def_property_readonly(
          "haar_kinds", [](const PyTransfer& t) { return haarColumn(t, 0); },
          "basis 'haar': (rows,) uint8, what each row holds: 0 its occluded part D = U - T (relit "
          "as the unshadowed light less D·L), 1 its visible part T (transfer/haar_rows.hpp).")
      .def_property_readonly(
          "haar_indices", [](const PyTransfer& t) { return haarColumn(t, 1); },
          "basis 'haar': (rows, K) uint32, each row's wavelet coefficients, ascending (padding: "
          "index 0 with value 0).")
      .def_property_readonly(
          "haar_values", [](const PyTransfer& t) { return haarColumn(t, 2); },
          "basis 'haar': (rows, K) float32, their values.")
      .def_property_readonly(
          "haar_bounce", [](const PyTransfer& t) { return haarColumn(t, 3); },
          "basis 'haar': (rows, B², channels) float32, each inter-reflected row's bounce in SH "
          "(B = haar['bounce_bands']; B = 0 gives (rows, 0, 1)), relit against the light's SH "
          "inside the albedo.")
      .def_property_readonly(
          "channels", [](const PyTransfer& t) { return t.transfer.channels(); },
          "1 (scalar) or 3 (RGB: coloured inter-reflection).")
      .def_property_readonly("first_row",
                             [](const PyTransfer& t) { return t.transfer.rows().first; })
      .def_property_readonly("row_count", [](const PyTransfer& t) { return t.transfer.rowCount(); })
      .def("__len__", [](const PyTransfer& t) { return t.transfer.rowCount(); })
      .def_property_readonly(
          "representation",
          [](const PyTransfer& t) { return t.transfer.compressed() ? "cpca" : "dense"; })
      .def_property_readonly("compressed",
                             [](const PyTransfer& t) { return t.transfer.compressed(); })
      .def_property_readonly(
          "shape",
          [](const PyTransfer& t) { return py::tuple(py::cast(denseShape(t.transfer.shape()))); },
          "The numpy shape of the dense rows.")
      .def_property_readonly(
          "nbytes", [](const PyTransfer& t) { return t.transfer.bytes(); },
          "Bytes as stored (compressed: ids, weights, means and bases).")
      .def_property_readonly(
          "values",
          [](py::object self) {
            const PyTransfer& t = self.cast<const PyTransfer&>();
            requireShTransfer(t,
                              "its rows are sparse wavelet terms (haar_kinds, haar_indices, "
                              "haar_values), not dense SH rows");
            if (t.transfer.compressed())
              throw py::value_error(
                  "the transfer is CPCA-compressed: to_dense() reconstructs its rows");
            return view(py::dtype::of<float>(), denseShape(t.transfer.shape()),
                        t.transfer.values().data(), self, false);
          },
          "The dense rows: a read-only view, no copy (np.array(t.values) to edit a copy).")
      .def(
          "__array__",
          [](py::object self, py::object dtype, py::object /*copy*/) {
            py::object v = self.attr("values");
            return dtype.is_none() ? v : v.attr("astype")(dtype);
          },
          py::arg("dtype") = py::none(), py::arg("copy") = py::none())
      .def_property_readonly(
          "clusters",
          [](const PyTransfer& t) {
            return t.transfer.compressed() ? t.transfer.cpca().clusters : 0;
          },
          "K, the CPCA cluster count (0 when dense).")
      .def_property_readonly(
          "basis_count",
          [](const PyTransfer& t) {
            return t.transfer.compressed() ? t.transfer.cpca().basisCount : 0;
          },
          "N, the principal components per cluster (0 when dense).")
      .def_property_readonly(
          "cluster_ids",
          [](py::object self) -> py::object {
            const PyTransfer& t = self.cast<const PyTransfer&>();
            if (!t.transfer.compressed()) return py::none();
            const auto& c = t.transfer.cpca().cluster;
            return view(py::dtype::of<std::uint32_t>(), {static_cast<py::ssize_t>(c.size())},
                        c.data(), self, false);
          },
          "(rows,) uint32 cluster of each row (CPCA), else None.")
      .def_property_readonly(
          "weights",
          [](py::object self) -> py::object {
            const PyTransfer& t = self.cast<const PyTransfer&>();
            if (!t.transfer.compressed()) return py::none();
            const auto& c = t.transfer.cpca();
            return cpcaArray(self, c.weights,
                             {static_cast<py::ssize_t>(t.transfer.rowCount()), c.basisCount});
          },
          "(rows, N) float32 weights w_rj (CPCA), else None.")
      .def_property_readonly(
          "means",
          [](py::object self) -> py::object {
            const PyTransfer& t = self.cast<const PyTransfer&>();
            if (!t.transfer.compressed()) return py::none();
            Shape s = rowShape(t.transfer.shape());
            s.insert(s.begin(), t.transfer.cpca().clusters);
            return cpcaArray(self, t.transfer.cpca().means, s);
          },
          "(K, *row) float32 cluster means M_k (CPCA), else None.")
      .def_property_readonly(
          "basis",
          [](py::object self) -> py::object {
            const PyTransfer& t = self.cast<const PyTransfer&>();
            if (!t.transfer.compressed()) return py::none();
            const auto& c = t.transfer.cpca();
            Shape s = rowShape(t.transfer.shape());
            s.insert(s.begin(), {c.clusters, c.basisCount});
            return cpcaArray(self, c.basis, s);
          },
          "(K, N, *row) float32 basis vectors B_kj (CPCA), else None: row r ≈ M_k + Σ_j w_rj B_kj.")
      .def_property_readonly("mode",
                             [](const PyTransfer& t) -> py::object {
                               if (!t.recipe) return py::none();
                               return py::str(prt::toString(t.recipe->mode));
                             })
      .def_property_readonly(
          "recipe",
          [](const PyTransfer& t) -> py::object {
            if (!t.recipe) return py::none();
            return recipeDict(*t.recipe);
          },
          "How it was baked (mode, samples, bounces, seed, sampling, material), or None.")
      .def_property_readonly(
          "stats",
          [](const PyTransfer& t) -> py::object {
            if (!t.stats) return py::none();
            return statsDict(*t.stats);
          },
          "The bake's statistics (rays, seconds, Monte Carlo standard errors), or None.")
      .def_property_readonly(
          "compression",
          [](const PyTransfer& t) -> py::object {
            if (!t.compression || !t.transfer.compressed()) return py::none();
            return compressionDict(*t.compression);
          },
          "How a compressed transfer was fitted and its error, or None.")
      .def(
          "cut",
          [](const PyTransfer& t, int b) {
            if (b < 1 || b > t.transfer.bands())
              throw py::value_error("cut(" + std::to_string(b) + "): must be 1.." +
                                    std::to_string(t.transfer.bands()));
            auto out = std::make_shared<PyTransfer>(t);
            out->transfer = t.transfer.cut(b);
            return out;
          },
          py::arg("bands"),
          "The first `bands` bands, in the same representation (exact for compressed rows).")
      .def(
          "to_dense",
          [](const PyTransfer& t) {
            auto out = std::make_shared<PyTransfer>(t);
            {
              py::gil_scoped_release nogil;
              out->transfer = t.transfer.toDense();
            }
            return out;
          },
          "The dense transfer (the reconstruction of compressed rows; a dense one shared).")
      .def("__repr__", [](const PyTransfer& t) {
        std::string s = "<prtkit.Transfer " + t.transfer.shape().describe();
        if (t.recipe) s += std::string(", ") + prt::toString(t.recipe->mode);
        if (t.transfer.compressed())
          s += ", CPCA K=" + std::to_string(t.transfer.cpca().clusters) +
               " N=" + std::to_string(t.transfer.cpca().basisCount);
        return s + ">";
      });

  m.def(
      "bake",
      [](py::object mesh, const std::string& mode, int bands, py::object samples,
         std::uint64_t seed, int bounces, const std::string& transfer, py::object spec,
         py::object albedo, const std::string& sampling, py::object range,
         const std::string& domain, int resolution, const std::string& uv, int padding,
         bool seamFix, bool denoise, py::object progress, double targetError,
         const std::string& basis, int cubeResolution, int terms) {
        if (basis == "haar")
          throw py::value_error(
              "basis='haar': bake returns dense SH rows, and a Haar transfer's rows are sparse "
              "wavelet terms: use bake_transfer (Transfer.haar_kinds, haar_indices, "
              "haar_values)");
        Baked b = runBake(mesh, mode, bands, samples, seed, bounces, transfer, spec, albedo,
                          sampling, range, domain, {resolution, uv, padding, seamFix, denoise},
                          targetError, {basis, cubeResolution, terms}, progress, nullptr);
        return transferArray(std::move(b.transfer), true);
      },
      py::arg("mesh"), py::arg("mode") = "shadowed", py::arg("bands") = 3,
      py::arg("samples") = py::none(), py::arg("seed") = 0, py::arg("bounces") = 1,
      py::arg("transfer") = "vector", py::arg("material") = py::none(),
      py::arg("albedo") = py::none(), py::arg("sampling") = "cosine", py::arg("range") = py::none(),
      py::arg("domain") = "vertices", py::arg("resolution") = 512, py::arg("uv") = "auto",
      py::arg("padding") = 2, py::arg("seam_fix") = false, py::arg("denoise") = false,
      py::arg("progress") = py::none(), py::arg("target_error") = 0.0, py::arg("basis") = "sh",
      py::arg("cube_resolution") = prt::kDefaultHaarResolution,
      py::arg("terms") = prt::kDefaultHaarTerms,
      (std::string(
           "Bakes per-vertex SH transfer and returns its dense rows as a numpy array, without a "
           "copy:\n"
           "float32 (N, B²) for scalar vectors, (N, B², 3) RGB vectors, (N, B², B²) matrices,\n"
           "(N, B², B², 3) RGB matrices; the array's base is a capsule owning the C++ buffer\n"
           "(writable). bake_transfer returns it with its recipe and statistics.\n") +
       kBakeArgs)
          .c_str());
  m.def(
      "bake_transfer",
      [](py::object mesh, const std::string& mode, int bands, py::object samples,
         std::uint64_t seed, int bounces, const std::string& transfer, py::object spec,
         py::object albedo, const std::string& sampling, py::object range,
         const std::string& domain, int resolution, const std::string& uv, int padding,
         bool seamFix, bool denoise, py::object progress, double targetError,
         const std::string& basis, int cubeResolution, int terms) {
        prt::BakeSettings s;
        Baked b = runBake(mesh, mode, bands, samples, seed, bounces, transfer, spec, albedo,
                          sampling, range, domain, {resolution, uv, padding, seamFix, denoise},
                          targetError, {basis, cubeResolution, terms}, progress, &s);
        auto t = std::make_shared<PyTransfer>();
        t->transfer = std::move(b.transfer);
        t->recipe = s;
        t->stats = b.stats;
        return t;
      },
      py::arg("mesh"), py::arg("mode") = "shadowed", py::arg("bands") = 3,
      py::arg("samples") = py::none(), py::arg("seed") = 0, py::arg("bounces") = 1,
      py::arg("transfer") = "vector", py::arg("material") = py::none(),
      py::arg("albedo") = py::none(), py::arg("sampling") = "cosine", py::arg("range") = py::none(),
      py::arg("domain") = "vertices", py::arg("resolution") = 512, py::arg("uv") = "auto",
      py::arg("padding") = 2, py::arg("seam_fix") = false, py::arg("denoise") = false,
      py::arg("progress") = py::none(), py::arg("target_error") = 0.0, py::arg("basis") = "sh",
      py::arg("cube_resolution") = prt::kDefaultHaarResolution,
      py::arg("terms") = prt::kDefaultHaarTerms,
      (std::string(
           "bake, returning a prtkit.Transfer (values, recipe, stats) for write_bake, relight,\n"
           "compress and validate.\n") +
       kBakeArgs)
          .c_str());

  m.def(
      "compress",
      [](py::handle transfer, int clusters, int pca, std::uint64_t seed, int iterations,
         double tolerance, py::object progress) {
        const TransferPtr src = toTransfer(transfer);
        requireShTransfer(*src, "CPCA compresses SH rows (a Haar row is already its K terms)");
        const prt::Transfer& t = src->transfer;
        if (t.compressed()) throw py::value_error("the transfer is already compressed");
        if (pca < 0 || static_cast<std::size_t>(pca) > t.stride())
          throw py::value_error("pca=" + std::to_string(pca) + ": the " +
                                prt::toString(t.layout()) + " transfer has " +
                                std::to_string(t.stride()) + " values per row");
        if (clusters < 1 || static_cast<std::size_t>(clusters) > t.rowCount())
          throw py::value_error("clusters=" + std::to_string(clusters) + ": must be 1.." +
                                std::to_string(t.rowCount()) + " (the rows)");
        if (iterations < 1) throw py::value_error("iterations must be at least 1");
        if (!(tolerance >= 0)) throw py::value_error("tolerance must be >= 0");
        prt::CpcaOptions opt;
        opt.clusters = clusters;
        opt.basisCount = pca;
        opt.seed = seed;
        opt.maxIterations = iterations;
        opt.tolerance = tolerance;
        auto out = std::make_shared<PyTransfer>();
        out->recipe = src->recipe;
        out->stats = src->stats;
        prt::CpcaRecord record;
        record.fit = opt;
        out->transfer = runLong("compress", progress, [&](const prt::ProgressFn& fn) {
          return prt::compressCpca(t, opt, &record.stats, nullptr, fn);
        });
        out->compression = record;
        return out;
      },
      py::arg("transfer"), py::arg("clusters") = 64, py::arg("pca") = 8, py::arg("seed") = 0,
      py::arg("iterations") = 30, py::arg("tolerance") = 1e-3, py::arg("progress") = py::none(),
      R"(CPCA-compresses a dense transfer (Sloan, Hall, Hart & Snyder 2003), as `prt compress`.

clusters: K; pca: N principal components per cluster (0: vector quantisation); seed of the
k-means++ seeding; iterations and tolerance of the reassignment loop. Returns a compressed
prtkit.Transfer (cluster_ids, weights, means, basis; .compression holds its error), which
relight, write_bake and to_dense take. GIL released; progress as for bake.)");
}

}  // namespace prtpy
