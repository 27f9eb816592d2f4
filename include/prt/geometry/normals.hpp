#pragma once
// Mesh clean-up shared by the loaders and usable on meshes built in memory.
//
// Vertex normals are angle-weighted (Thürmer & Wüthrich, "Computing Vertex Normals from Polygonal
// Facets", JGT 3(1), 1998): n_v ∝ Σ_f α_f(v) n_f over the faces f around v, where α_f(v) is the
// face's interior angle at v. Unlike area or uniform weights, the result depends only on the
// surface's shape, not on how it was triangulated.

#include <cstddef>

#include "prt/geometry/mesh.hpp"

namespace prt {

/// True if the triangle has (numerically) zero area: repeated indices, or |e1 × e2| below
/// 1e-7·|longest edge|² (the rounding level of float coordinates).
bool isDegenerateTriangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2);

/// Removes zero-area triangles (and shrinks the parts' triangle ranges); returns how many.
std::size_t removeDegenerateTriangles(Mesh& mesh);

/// Angle-weighted vertex normals of all vertices (vertices on no triangle get +Y). Sizes
/// mesh.normals to the vertex count. Returns the number of vertices on no triangle.
std::size_t computeVertexNormals(Mesh& mesh);

/// Keeps the file's normals where they are finite and non-zero (normalising them) and replaces
/// the others by angle-weighted ones; returns how many were replaced.
std::size_t repairNormals(Mesh& mesh);

}  // namespace prt
