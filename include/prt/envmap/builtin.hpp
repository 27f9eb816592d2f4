#pragma once
// Built-in environments, named "builtin:NAME" wherever a path is accepted, with optional
// parameters as a query string: "builtin:sky?turbidity=3&elevation=30&azimuth=120".
//
//  builtin:sky       Preetham sky with sun (sky.hpp). Parameters: turbidity, elevation, azimuth
//                    (degrees), sun (∫ L dω of the disc), sunsize (angular radius, degrees),
//                    sky (zenith luminance), ground (albedo below the horizon).
//  builtin:constant  A uniform environment. Parameters: value (grey), or r, g, b. Default 1.
//  builtin:studio    Three round area lights (key, fill, rim) over a dim gradient.
//                    Parameter: intensity (scale, default 1).

#include <string>
#include <vector>

#include "prt/envmap/environment.hpp"

namespace prt::envmap {

/// True when `spec` starts with "builtin:".
bool isBuiltin(const std::string& spec);
/// The names known after "builtin:".
std::vector<std::string> builtinNames();
/// Builds the environment; texels are a lat-long sampling of width `texelWidth`.
/// Throws prt::Error("builtin:NAME: ...") for unknown names or parameters.
Environment builtinEnvironment(const std::string& spec, int texelWidth = 512);
/// The environment `builtin:sky` gives with no parameters: the default light.
inline constexpr const char* kDefaultEnvironment = "builtin:sky";

}  // namespace prt::envmap
