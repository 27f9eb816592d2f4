#include "prt/transfer/bake_settings.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "prt/core/error.hpp"

namespace prt {

void checkRecipe(const BakeRecipe& r) {
  if (r.samples < 1 || r.samples > kMaxBakeSamples)
    throw Error("samples must be in 1.." + std::to_string(kMaxBakeSamples) + ", got " +
                std::to_string(r.samples));
  if (r.bounces < 0 || r.bounces > kMaxBounces)
    throw Error("bounces must be in 0.." + std::to_string(kMaxBounces) + ", got " +
                std::to_string(r.bounces));
  if (!(r.targetError >= 0 && r.targetError <= kMaxTargetError)) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", r.targetError);
    throw Error("the target error must be in [0, 1] (0: no adaptive sampling), got " +
                std::string(got));
  }
  checkMaterial(r.material);
}

const char* toString(TransferMode mode) {
  switch (mode) {
    case TransferMode::Unshadowed:
      return "unshadowed";
    case TransferMode::Shadowed:
      return "shadowed";
    case TransferMode::Interreflected:
      return "interreflected";
  }
  return "?";
}

TransferMode parseTransferMode(const std::string& s) {
  if (s == "unshadowed") return TransferMode::Unshadowed;
  if (s == "shadowed") return TransferMode::Shadowed;
  if (s == "interreflected") return TransferMode::Interreflected;
  throw Error("unknown transfer mode '" + s +
              "' (expected unshadowed, shadowed or interreflected)");
}

const char* toString(Sampling sampling) {
  switch (sampling) {
    case Sampling::CosineSobol:
      return "cosine-sobol";
    case Sampling::UniformRandom:
      return "uniform-random";
  }
  return "?";
}

Sampling parseSampling(const std::string& s) {
  if (s == "cosine" || s == "sobol" || s == "cosine-sobol") return Sampling::CosineSobol;
  if (s == "uniform" || s == "uniform-random") return Sampling::UniformRandom;
  throw Error("unknown sampling '" + s + "' (expected cosine-sobol or uniform-random)");
}

BakeStats combineBakeStats(const BakeStats& a, std::size_t rowsA, const BakeStats& b,
                           std::size_t rowsB) {
  BakeStats x = a;
  const double wa = static_cast<double>(rowsA), wb = static_cast<double>(rowsB);
  const auto mean = [&](double u, double v) {
    return wa + wb > 0 ? (u * wa + v * wb) / (wa + wb) : 0.0;
  };
  x.stdErrT0Mean = mean(a.stdErrT0Mean, b.stdErrT0Mean);
  x.stdErrConstMean = mean(a.stdErrConstMean, b.stdErrConstMean);
  x.stdErrT0Max = std::max(a.stdErrT0Max, b.stdErrT0Max);
  x.stdErrConstMax = std::max(a.stdErrConstMax, b.stdErrConstMax);
  // The rate over the ray-casting time of both pieces (each piece's rays / its rate).
  const double raySeconds = (a.raysPerSecond > 0 ? a.rays / a.raysPerSecond : 0) +
                            (b.raysPerSecond > 0 ? b.rays / b.raysPerSecond : 0);
  x.rays = a.rays + b.rays;
  x.raysPerSecond = raysPerSecondOf(x.rays, raySeconds);
  x.secondsTotal = a.secondsTotal + b.secondsTotal;
  x.secondsDirect = a.secondsDirect + b.secondsDirect;
  for (std::size_t k = 0; k < b.secondsBounce.size(); ++k) {
    if (x.secondsBounce.size() <= k) x.secondsBounce.push_back(0);
    x.secondsBounce[k] += b.secondsBounce[k];
  }
  for (std::size_t k = 0; k < b.raysBounce.size(); ++k) {
    if (x.raysBounce.size() <= k) x.raysBounce.push_back(0);
    x.raysBounce[k] += b.raysBounce[k];
  }
  x.vertices = a.vertices + b.vertices;
  x.threads = std::max(a.threads, b.threads);
  return x;
}

TransferShape BakeSettings::inBasis(TransferShape shape) const {
  shape.basis = basis;
  shape.bands = basis == TransferBasis::Haar ? 0 : bands;
  shape.haar = basis == TransferBasis::Haar ? haar : TransferShape::HaarSize{};
  return shape;
}

}  // namespace prt
