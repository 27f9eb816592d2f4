// prt reference: exit radiance per vertex, or per texel of a per-texel bake (at the texels'
// sample points, a subset among the valid ones), by brute-force Monte Carlo, no SH
// (render/reference.hpp; docs/validation.md).
//
//   prt reference BAKE.glb --light ENV [--mode M] [--samples N] [--rotate X,Y,Z]
//                 [--material SPEC] [--eye X,Y,Z] [--vertices N] [--seed S]
//                 [--mis power|balance] -o radiance.json|.bin
//
// A glossy --material (transfer/material.hpp) is seen from --eye, by default the eye of the
// default camera of `prt render` (render::frameMesh at its default 640x480), so the numbers are
// those of the default render's view.
//
// Outputs, one entry per estimated vertex (io/reference_file.hpp): .json, which names the bake
// and environment it is for and which `prt validate --reference` and `prt render --reference`
// read instead of recomputing, or .bin (the numbers alone).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "mpi_verb.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/json.hpp"
#include "prt/core/version.hpp"
#include "prt/envmap/load.hpp"
#include "prt/image/color.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/io/reference_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/reference.hpp"
#include "prt/render/validate.hpp"
#include "prt/transfer/material.hpp"
#include "report.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

struct ReferenceArgs {
  std::string bake, light, output, rotate, material, eye, mis = "power", json;
  TransferChoice transfer;
  int samples = 1024;
  std::size_t vertices = 0;
  std::uint64_t seed = 0;
};

void referenceBody(const ReferenceArgs& a, MpiVerb& mpi) {
  if (a.samples < 1) throw Error("--samples must be at least 1");
  const std::string ext = isStandardOutput(a.output) ? "json" : fileExtension(a.output);
  if (ext != "json" && ext != "bin") throw Error(a.output, "output must be .json or .bin");
  refuseShLight(a.light, "reference");
  checkOutputs({{"-o", a.output}}, {{"input", a.bake}, {"--light", a.light}});
  checkWritable(a.output);
  Report report("reference", a.json);
  report.check({{"-o", a.output}}, {{"input", a.bake}, {"--light", a.light}});
  const Mat3d rotation = parseRotation(a.rotate);
  const render::MisHeuristic mis = parseMis(a.mis);
  if (!a.material.empty()) parseMaterial(a.material);  // a bad spec fails before the bake is read
  std::optional<Vec3f> eye;
  if (!a.eye.empty()) {
    const std::vector<double> e = parseNumberList(a.eye, "--eye");
    if (e.size() != 3) throw Error("--eye '" + a.eye + "' is not three numbers X,Y,Z");
    eye = Vec3f(Vec3d(e[0], e[1], e[2]));
  }

  // Mapped: the reference reads the mesh and the transfer's shape, never its rows.
  const BakeFile file = mapBake(a.bake);
  file.requireSurface(a.bake, "prt reference integrates the light a surface sends");
  const BakedTransfer& bt = pickTransfer(file, a.transfer, a.bake);
  const char* row = rowName(bt.transfer.domain());
  const envmap::LoadedEnvironment env = envmap::loadEnvironment(a.light);
  for (const std::string& w : envmap::repairWarnings(env)) warn(w);
  auto occluder = makeEmbreeOccluder(file.mesh);

  render::ReferenceSettings rs;
  rs.samples = a.samples;
  rs.mode = bt.mode();
  rs.bounces = bt.recipe.effectiveBounces();
  // The bake stores its material (kd, ks and the lobe, at full precision); --material replaces
  // it, keeping the bake's kd unless it names its own.
  const Material chosen =
      materialOption(a.material, bt, a.bake,
                     "the reference follows --material at every bounce, the bake does not");
  warnLobeOnVectors(chosen, bt, a.bake,
                    "the reference of vector transfer is its diffuse part, as its relighting is");
  rs.material = render::referenceMaterial(chosen, bt.transfer.layout());
  // The default view: the eye of `prt render`'s default camera (its default --size 640x480).
  rs.eye = eye ? *eye : render::frameMesh(file.mesh, 640, 480).eye;
  rs.seed = a.seed;
  rs.rotation = rotation;
  rs.heuristic = mis;
  // Per-texel transfer: the rows are the texels' sample points (render/texel_points.hpp), and a
  // subset is drawn among the valid ones (--vertices counts texels then), as prt validate draws
  // it: render::chooseRows, which places the points of those texels alone.
  render::RowChoice rows =
      render::chooseRows(file.mesh, *occluder, bt.transfer, a.vertices, a.seed);
  rs.vertices = std::move(rows.rows);
  rs.points = std::move(rows.points);
  const render::ReferenceResult r =
      mpi.reference(file.mesh, *occluder, env.env, rs, progressBar("reference"));
  if (!mpi.root()) return;
  for (std::size_t i = 0; i < r.radiance.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(r.radiance[i][c]) || !std::isfinite(r.stdError[i][c]))
        throw Error(a.light, std::string("the radiance at ") + row + " " +
                                 std::to_string(r.vertices[i]) +
                                 " is not finite (the environment is too bright for 32-bit "
                                 "floats); nothing written");
  io::ReferenceFile ref;
  ref.prtkitVersion = kVersion;
  ref.bakeFile = a.bake;
  ref.meshVertices = file.mesh.vertexCount();
  ref.meshFingerprint = meshFingerprint(file.mesh);
  ref.setRows(file.mesh, bt.transfer.shape());
  ref.lightSource = a.light;
  ref.environmentFingerprint = io::environmentFingerprint(env.env);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) ref.rotation[3 * i + k] = rotation.m[i][k];
  ref.mode = toString(rs.mode);
  ref.bounces = rs.bounces;
  ref.material = rs.material.spec();
  if (rs.material.glossy()) ref.eye = rs.eye;
  ref.samples = a.samples;
  ref.seed = a.seed;
  ref.mis = a.mis;
  ref.rays = r.rays;
  ref.seconds = r.seconds;
  ref.vertices = r.vertices;
  ref.radiance = r.radiance;
  ref.stdError = r.stdError;
  if (ext == "json")
    io::writeReferenceJson(a.output, ref);
  else
    io::writeReferenceBinary(a.output, ref);
  char line[200];
  std::snprintf(line, sizeof line, "wrote %s: %zu %s x %d samples, %llu rays, %.2f s",
                a.output.c_str(), r.vertices.size(), toString(bt.transfer.domain()), a.samples,
                static_cast<unsigned long long>(r.rays), r.seconds);
  info(line);
  if (report.wanted()) {
    report.input(a.bake);
    report.input(a.light);
    report.output(a.output);
    report["mode"] = toString(rs.mode);
    report["bounces"] = rs.bounces;
    report["material"] = rs.material.spec();
    report["samples"] = a.samples;
    report["seed"] = a.seed;
    report[toString(bt.transfer.domain())] = r.vertices.size();
    report["rays"] = r.rays;
    report["seconds"] = r.seconds;
    if (mpi.active()) report["mpiRanks"] = mpi.size();
    // Luminance of the radiance and of its standard error, over the estimated vertices.
    double sum = 0, errSum = 0, errMax = 0;
    for (std::size_t i = 0; i < r.radiance.size(); ++i) {
      sum += image::luminance(r.radiance[i]);
      const double e = image::luminance(r.stdError[i]);
      errSum += e;
      errMax = std::max(errMax, e);
    }
    const double n = std::max<double>(1, r.radiance.size());
    report["meanLuminance"] = sum / n;
    report["stdErrLuminanceMean"] = errSum / n;
    report["stdErrLuminanceMax"] = errMax;
    report.write();
  }
}

void runReference(const ReferenceArgs& a) {
  MpiVerb mpi("prt reference");
  mpi.run([&] { referenceBody(a, mpi); });
}

}  // namespace

void addReferenceCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "reference",
      "Exit radiance per vertex (or per texel) by brute-force Monte Carlo (no SH), for "
      "validation");
  auto a = std::make_shared<ReferenceArgs>();
  cmd->add_option("bake", a->bake, "Bake file (.glb): its mesh and transport settings")->required();
  cmd->add_option("--light", a->light, "Environment: image, face folder or builtin:NAME")
      ->required();
  addTransferChoice(cmd, a->transfer, "whose transport the reference follows");
  cmd->add_option("--samples", a->samples, "Samples per vertex (texel)")
      ->check(intRange(1, 1 << 24))
      ->capture_default_str();
  cmd->add_option("--rotate", a->rotate, "Rotate the environment: Euler X,Y,Z degrees");
  cmd->add_option("--vertices", a->vertices,
                  "Estimate a deterministic random subset of N vertices (0: all); of a per-texel "
                  "bake, N of its valid texels")
      ->check(unsignedInt(UINT32_MAX));
  addMaterialOption(cmd, a->material, "the reference renders");
  cmd->add_option("--eye", a->eye,
                  "Camera position X,Y,Z for a glossy material's view directions (default: the "
                  "eye of prt render's default camera)");
  cmd->add_option("--seed", a->seed, "Seed")->check(unsignedInt())->capture_default_str();
  cmd->add_option("--mis", a->mis, "MIS heuristic: power | balance")->capture_default_str();
  cmd->add_option("-o,--output", a->output, "Output .json or .bin")->required();
  addJsonOption(cmd, a->json);
  cmd->callback([a] { runReference(*a); });
}

}  // namespace prt::cli
