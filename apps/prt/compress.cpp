// prt compress: a bake's transfer → CPCA-compressed transfer (Sloan, Hall, Hart & Snyder 2003).
//
//   prt compress bunny.glb --clusters 256 --pca 8 -o bunny-cpca.glb
//   prt compress bunny.glb --target-error 0.01 -o bunny-cpca.glb       (smallest K, N meeting it)
//   prt compress bunny.glb --sweep sweep.png                            (error/size table + plot)
//
// The picked transfer (--mode, --transfer; default as every verb: the richest, a matrix before a
// vector) is replaced by its compressed form; the other transfers are copied unchanged. The
// output is a version-3 bake file (docs/formats-bake.md); docs/compress.md explains the choices.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "report.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/image/image.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

struct CompressArgs {
  std::string bake, output, sweep, sweepClusters = "1,4,16,64,256", json;
  TransferChoice transfer;
  int clusters = 64, basis = 8, iterations = 30, maxBasis = 16;
  std::uint64_t seed = 0;
  double targetError = 0, tolerance = 1e-3;
};

// Line colours of the plot, one per K (cycled).
const Rgb kColours[] = {{0.12f, 0.47f, 0.71f}, {1.0f, 0.5f, 0.05f},  {0.17f, 0.63f, 0.17f},
                        {0.84f, 0.15f, 0.16f}, {0.58f, 0.4f, 0.74f}, {0.55f, 0.34f, 0.29f},
                        {0.89f, 0.47f, 0.76f}, {0.5f, 0.5f, 0.5f}};
const char* kColourNames[] = {"blue", "orange", "green", "red", "purple", "brown", "pink", "grey"};

void line(image::Image& img, double x0, double y0, double x1, double y1, Rgb c, int width = 2) {
  const int steps = static_cast<int>(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    for (int dy = 0; dy < width; ++dy)
      for (int dx = 0; dx < width; ++dx)
        if (x + dx >= 0 && x + dx < img.width && y + dy >= 0 && y + dy < img.height)
          img.at(x + dx, y + dy) = c;
  }
}

/// The sweep as a picture: x = stored bytes per vertex (log2), y = relative RMS error (log10),
/// one polyline per K; grid lines at powers of 2 bytes and decades of error; the target error,
/// if any, as a black horizontal line.
image::Image plotSweep(const std::vector<CpcaSweepPoint>& pts, std::size_t rows, double target) {
  const int W = 900, H = 560, m = 40;
  image::Image img(W, H, Rgb(1.0f));
  double bx0 = 1e300, bx1 = 0, ey0 = 1e300, ey1 = 0;
  for (const auto& p : pts) {
    const double b = static_cast<double>(p.bytes) / rows;
    const double e = std::max(p.stats.relativeRms, 1e-7);
    bx0 = std::min(bx0, b), bx1 = std::max(bx1, b), ey0 = std::min(ey0, e), ey1 = std::max(ey1, e);
  }
  if (target > 0) ey0 = std::min(ey0, target), ey1 = std::max(ey1, target);
  const double lx0 = std::floor(std::log2(bx0)), lx1 = std::ceil(std::log2(bx1)) + (bx0 == bx1);
  const double ly0 = std::floor(std::log10(ey0)), ly1 = std::ceil(std::log10(ey1)) + (ey0 == ey1);
  auto X = [&](double b) { return m + (std::log2(b) - lx0) / (lx1 - lx0) * (W - 2 * m); };
  auto Y = [&](double e) {
    return H - m - (std::log10(std::max(e, 1e-7)) - ly0) / (ly1 - ly0) * (H - 2 * m);
  };
  const Rgb grid(0.85f), axis(0.0f);
  for (double l = lx0; l <= lx1; ++l)
    line(img, X(std::exp2(l)), m, X(std::exp2(l)), H - m, grid, 1);
  for (double l = ly0; l <= ly1; ++l)
    line(img, m, Y(std::pow(10.0, l)), W - m, Y(std::pow(10.0, l)), grid, 1);
  line(img, m, H - m, W - m, H - m, axis, 2);
  line(img, m, m, m, H - m, axis, 2);
  if (target > 0) line(img, m, Y(target), W - m, Y(target), axis, 1);
  int series = -1, lastK = -1;
  double px = 0, py = 0;
  for (const auto& p : pts) {
    const double x = X(static_cast<double>(p.bytes) / rows), y = Y(p.stats.relativeRms);
    if (p.clusters != lastK)
      ++series, lastK = p.clusters;
    else
      line(img, px, py, x, y, kColours[series % 8], 2);
    line(img, x - 3, y - 3, x + 3, y + 3, kColours[series % 8], 2);  // a mark per point
    line(img, x - 3, y + 3, x + 3, y - 3, kColours[series % 8], 2);
    px = x, py = y;
  }
  return img;
}

std::vector<int> parseClusterList(const std::string& s, std::size_t rows) {
  std::vector<int> out;
  for (double x : parseNumberList(s, "--sweep-clusters")) {
    if (x < 1 || x != std::floor(x) || x > 1e7)
      throw Error(fmt::format("--sweep-clusters: {} is not a cluster count", x));
    if (x <= static_cast<double>(rows)) out.push_back(static_cast<int>(x));
  }
  if (out.empty()) throw Error("--sweep-clusters: no count fits the bake's rows");
  return out;
}

void runCompress(const CompressArgs& a, bool clustersGiven, bool basisGiven) {
  const bool sweeping = !a.sweep.empty();
  // The tables go to standard output, unless the bake or the report does (-o -, --json -).
  Report report("compress", a.json);
  std::ostream& table =
      isStandardOutput(a.output) || report.toStandardOutput() ? std::cerr : std::cout;
  if (a.output.empty() && !sweeping) throw Error("prt compress needs -o OUTPUT.glb (or --sweep)");
  if (!a.output.empty() && fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the bake file must end in .glb");
  if (sweeping && fileExtension(a.sweep) != "png")
    throw Error(a.sweep + ": --sweep writes a PNG plot (name it .png)");
  if (a.targetError > 0 && (clustersGiven || basisGiven))
    throw Error("--target-error chooses --clusters and --pca itself; give one or the other");
  checkOutputs({{"-o", a.output}, {"--sweep", a.sweep}}, {{"input", a.bake}});
  if (!a.output.empty()) checkWritable(a.output);
  if (sweeping) checkWritable(a.sweep);
  report.check({{"-o", a.output}, {"--sweep", a.sweep}}, {{"input", a.bake}});
  report.input(a.bake);

  BakeFile bake = readBake(a.bake);
  // The clusters are fitted to every row: a piece compressed alone could not be merged with the
  // others (each has its own cluster table), so pieces are merged first.
  bake.requireComplete(a.bake);
  bake.requireSh(a.bake, "prt compress fits SH transfer");
  const BakedTransfer& picked = pickTransfer(bake, a.transfer, a.bake);
  if (picked.transfer.compressed())
    throw Error(a.bake, "the " + picked.describe() + " transfer is already compressed");
  const Transfer& field = picked.transfer;
  const std::size_t D = field.stride(), rows = field.rowCount();
  if (a.basis > static_cast<int>(D))
    throw Error(fmt::format("--pca {}: the {} transfer has only {} values per {}", a.basis,
                            toString(field.layout()), D, rowName(field.domain())));
  if (static_cast<std::size_t>(a.clusters) > rows)
    throw Error(fmt::format("--clusters {}: the bake has only {} {}", a.clusters, rows,
                            toString(field.domain())));
  info(fmt::format("{}: {} {} transfer, {} bands x {} channel(s) = {} values per {}, {} {}",
                   a.bake, toString(picked.mode()), toString(field.layout()), field.bands(),
                   field.channels(), D, rowName(field.domain()), rows, toString(field.domain())));

  CpcaOptions opt;
  opt.clusters = a.clusters;
  opt.basisCount = a.basis;
  opt.seed = a.seed;
  opt.maxIterations = a.iterations;
  opt.tolerance = a.tolerance;
  bool chain = false;
  if (sweeping || a.targetError > 0) {
    const std::vector<int> ks = parseClusterList(a.sweepClusters, rows);
    const int maxN = std::min<int>(a.maxBasis, static_cast<int>(D));
    const auto pts =
        sweepCpca(field, ks, maxN, opt, sweeping ? 0 : a.targetError, progressBar("sweeping"));
    Json sweep = Json::array();
    for (const auto& p : pts)
      sweep.push_back({{"clusters", p.clusters},
                       {"components", p.basisCount},
                       {"bytes", p.bytes},
                       {"bytesPerRow", static_cast<double>(p.bytes) / rows},
                       {"relativeRms", p.stats.relativeRms},
                       {"snrDb", std::isfinite(p.stats.snrDb) ? Json(p.stats.snrDb) : Json()},
                       {"ratio", p.stats.compressionRatio},
                       {"seconds", p.stats.seconds}});
    report["sweep"] = std::move(sweep);
    if (sweeping) {
      table << fmt::format("{:>7} {:>4} {:>12} {:>10} {:>9} {:>9} {:>8}  {}\n", "K", "N",
                           "bytes/vertex", "rel. RMS", "SNR dB", "ratio", "seconds", "colour");
      int series = -1, lastK = -1;
      for (const auto& p : pts) {
        if (p.clusters != lastK) ++series, lastK = p.clusters;
        table << fmt::format("{:>7} {:>4} {:>12.2f} {:>10.3e} {:>9.2f} {:>9.2f} {:>8.2f}  {}\n",
                             p.clusters, p.basisCount, static_cast<double>(p.bytes) / rows,
                             p.stats.relativeRms, p.stats.snrDb, p.stats.compressionRatio,
                             p.stats.seconds, kColourNames[series % 8]);
      }
      image::WriteOptions wo;
      wo.toneMap = image::ToneMap::Clamp;
      image::writeImage(a.sweep, plotSweep(pts, rows, a.targetError), wo);
      report.output(a.sweep);
      info(
          fmt::format("wrote {} (x: stored bytes per vertex, log2; y: relative RMS error, log10; "
                      "one line per K in the colours above{})",
                      a.sweep, a.targetError > 0 ? "; black: the target error" : ""));
    }
    if (a.targetError > 0) {
      const CpcaSweepPoint* best = nullptr;
      for (const auto& p : pts)
        if (p.stats.relativeRms <= a.targetError && (!best || p.bytes < best->bytes)) best = &p;
      if (!best)
        throw Error(fmt::format(
            "--target-error {}: no K in {} with N <= {} meets it (best {:.3e}); allow more "
            "clusters (--sweep-clusters) or components (--max-pca)",
            a.targetError, a.sweepClusters, maxN,
            std::min_element(pts.begin(), pts.end(), [](const auto& x, const auto& y) {
              return x.stats.relativeRms < y.stats.relativeRms;
            })->stats.relativeRms));
      opt.clusters = best->clusters;
      opt.basisCount = best->basisCount;
      chain = true;
      report["targetError"] = a.targetError;
      info(fmt::format("--target-error {}: K = {}, N = {} ({:.2f} bytes per vertex)", a.targetError,
                       opt.clusters, opt.basisCount, static_cast<double>(best->bytes) / rows));
    }
    if (a.output.empty()) {
      report.write();
      return;
    }
  }

  CpcaStats stats;
  Transfer c = chain ? compressCpcaChain(field, opt, stats, progressBar("compressing"))
                     : compressCpca(field, opt, &stats, nullptr, progressBar("compressing"));
  table << fmt::format(
      "K {} N {}: relative RMS error {:.4e}, SNR {:.2f} dB, squared error {:.6e}, max vertex "
      "error {:.4e}, {} -> {} bytes (ratio {:.2f}), {} iterations, {:.2f} s\n",
      opt.clusters, opt.basisCount, stats.relativeRms, stats.snrDb, stats.squaredError,
      stats.maxRowError, rows * D * 4, c.bytes(), stats.compressionRatio, stats.iterations,
      stats.seconds);
  for (BakedTransfer& t : bake.transfers)
    if (&t == &picked) {
      t.transfer = std::move(c);
      t.compression = {opt, stats};
    }
  writeBake(a.output, bake);
  info(fmt::format("wrote {}", a.output));
  report.output(a.output);
  report["transfer"] = transferJson(picked);
  report.write();
}

}  // namespace

void addCompressCommand(CLI::App& root) {
  auto args = std::make_shared<CompressArgs>();
  auto* cmd = root.add_subcommand(
      "compress", "Compress a bake's transfer by clustered PCA (Sloan et al. 2003)");
  cmd->add_option("bake", args->bake, "Bake file (.glb)")->required();
  auto* k = cmd->add_option("--clusters", args->clusters, "Clusters K")
                ->check(intRange(1, 1 << 24))
                ->capture_default_str();
  auto* n = cmd->add_option("--pca", args->basis, "Principal components N per cluster (0 = VQ)")
                ->check(intRange(0, 1 << 20))
                ->capture_default_str();
  addTransferChoice(cmd, args->transfer, "to compress");
  cmd->add_option("--seed", args->seed, "Seed of the initial clusters")
      ->check(unsignedInt())
      ->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Most reassignment passes")
      ->check(intRange(0, 10000))
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "Converged when a pass lowers the error by less than this fraction (0: until "
                  "no vertex moves)")
      ->check(finite(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--target-error", args->targetError,
                  "Pick the smallest K, N whose relative RMS error is at most this")
      ->check(finite(1e-9, 1.0));
  cmd->add_option("--sweep", args->sweep,
                  "Print the error/size table over K and N and plot it to this PNG");
  cmd->add_option("--sweep-clusters", args->sweepClusters,
                  "Cluster counts for --sweep/--target-error")
      ->capture_default_str();
  cmd->add_option("--max-pca", args->maxBasis, "Largest N for --sweep/--target-error")
      ->check(intRange(0, 1 << 20))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output bake file (.glb)");
  addJsonOption(cmd, args->json);
  cmd->callback([args, k, n] { runCompress(*args, k->count() > 0, n->count() > 0); });
}

}  // namespace prt::cli
