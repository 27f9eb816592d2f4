#pragma once
// Builtin scenes, generated in code so tests, demos and benchmarks need no files. Accepted
// wherever a mesh path is, as "builtin:NAME" or "builtin:NAME?key=value&key=value".
//
//   sphere        unit sphere at the origin: a subdivided icosahedron (near-uniform triangles),
//                 analytic normals. Parameters: subdiv (default 5: 10242 vertices, 20480
//                 triangles), r (radius, default 1), albedo (grey level, default 0.8).
//   sphere-plane  a sphere of radius r (default 0.5) centred at height h (default 1) above the
//                 square plane y = 0 of half-size `size` (default 4), tessellated as a grid of
//                 `grid` x `grid` quads (default 96) so per-vertex bakes resolve the shadow.
//                 Parameters: r, h, size, grid, subdiv (default 4), albedo (default 0.8). The
//                 shadow of a distant light from +Y is a disc of radius r under the sphere;
//                 the gap between sphere and plane is h - r (h > r required).
//   plane         a ground plane y = `y` (default 0) facing +Y, half-size `size` (default 4),
//                 `grid` x `grid` quads (default 96), albedo (default 0.8): put it under a mesh
//                 ("bunny.obj builtin:plane?y=-1&size=3") so the object casts a shadow.
//   cornell       a Cornell-like box for colour bleeding and self-shadowing: floor, ceiling and
//                 back wall white (0.73), left wall (x = -1) red (0.63, 0.065, 0.05), right wall
//                 (x = +1) green (0.14, 0.45, 0.091), open toward +Z (the camera side); the box
//                 spans [-1, 1] x [0, 2] x [-1, 1]; a tall and a short block stand inside, rotated
//                 about Y. Parameter: grid (wall tessellation, default 40).
//
// All scenes are +Y up, counter-clockwise front faces, unit normals, per-vertex linear albedo,
// one MeshPart per object (named "sphere", "plane", "floor", "tall-block", ...). `plane` and
// `cornell` carry lightmap UVs (Mesh::lightmapUvs): each grid one chart, packed at one texel
// density (geometry/chart_packing.hpp); the sphere scenes none (the icosphere has no seams).

#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt {

/// The names builtinScene() accepts (without "builtin:" and parameters).
std::vector<std::string> builtinSceneNames();

/// True if `path` starts with "builtin:".
bool isBuiltinScene(const std::string& path);

/// Generates a builtin scene. `name` may carry the "builtin:" prefix and "?key=value&..."
/// parameters. Throws prt::Error naming the scene for unknown names, unknown or bad parameters.
Mesh builtinScene(const std::string& name);

}  // namespace prt
