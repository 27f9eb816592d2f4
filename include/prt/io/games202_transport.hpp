#pragma once
// The GAMES202 course's transport.txt (homework 2, "PRT"), read and written in its exact layout.
//
// The course's nori preprocessor writes, for a mesh of V vertices and T triangles:
//
//   V                                  first line: the vertex count of the OBJ as nori loads it
//   t0 t1 ... t8 ␠\n                   then 3·T lines, one per triangle corner, in face order:
//   ...                                the B² transfer coefficients of that corner's vertex,
//                                      each followed by one space
//
// ("Save in face format" in the course's prt.cpp; its WebGL side reads the numbers after the
// first as a non-indexed vertex attribute, 27 per triangle.) The vertex count on the first line
// is therefore not the number of lines. We write that layout (Faces) by default, and also a
// per-vertex layout (Vertices: V lines in vertex order) for tools that index the mesh
// themselves. Vertex order is the OBJ loader's: one vertex per distinct v/vt/vn index triple in
// order of first appearance, which is what prt's OBJ loader produces, so an OBJ bake exports in
// the course's order. Numbers are written with %.9g, enough to round-trip every float.
//
// The course's transfer carries the same 1/π as ours (T_i = (1/π)∫ Y_i V max(n·ω,0) dω), and its
// SHOrder = 2 is bands = 3; other band counts are written as B² numbers per line. The course
// has scalar transfer only: RGB transfer must be reduced to one channel first (selectChannel).

#include <cstddef>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

enum class Games202Layout {
  Faces,     ///< the course's file: 3 lines per triangle, in face order
  Vertices,  ///< one line per vertex
};

/// A parsed transport.txt.
struct Games202Transport {
  std::size_t vertexCount = 0;  ///< the first line
  int bands = 0;                ///< from the numbers per line (B²)
  Games202Layout layout = Games202Layout::Faces;
  std::size_t rowCount = 0;  ///< lines after the first
  std::vector<float> rows;   ///< rowCount × B²
};

/// How an RGB transfer becomes scalar for formats that hold one.
enum class ChannelSelect { Luminance, Red, Green, Blue };
/// Parses "luminance" | "r" | "g" | "b"; throws prt::Error otherwise.
ChannelSelect parseChannelSelect(const std::string& s);
/// A scalar transfer from dense vectors: itself if scalar; else one channel, or the Rec. 709
/// luminance 0.2126 R + 0.7152 G + 0.0722 B of each coefficient (linear, so relighting a grey
/// environment with it gives the luminance of the RGB result).
Transfer selectChannel(const Transfer& field, ChannelSelect channel);

/// The file's text. `field` must be dense scalar vectors covering every vertex of `mesh`
/// (matrices and compressed rows are refused: reduce them first; prt export writes a matrix's
/// diffuse part, relight::diffuseTransfer).
std::string formatGames202Transport(const Transfer& field, const Mesh& mesh,
                                    Games202Layout layout = Games202Layout::Faces);
/// Writes it atomically.
void writeGames202Transport(const std::string& path, const Transfer& field, const Mesh& mesh,
                            Games202Layout layout = Games202Layout::Faces);

/// Parses and validates: a positive vertex count, then lines of equally many numbers (a square
/// B²), all finite, the last ending in a newline (else the file was cut short); the layout is
/// Vertices if there are exactly vertexCount lines, else Faces (which needs a multiple of 3 and
/// more lines than vertices: fewer is a truncated file). `name` is used in messages
/// ("NAME:LINE: ...").
Games202Transport parseGames202Transport(const std::string& text, const std::string& name);
Games202Transport readGames202Transport(const std::string& path);

}  // namespace prt
