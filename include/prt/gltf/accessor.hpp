#pragma once
// Checked reads of glTF 2.0 accessors (§3.6.2): the one reader behind the mesh loader
// (geometry, any glTF) and the bake file (io, prtkit's own .glb). A file is untrusted input, so
// before a byte is read or an element allocated every reference and size it declares is checked:
//
//   accessor index → sparse (refused) → type and component type known → bufferView → buffer →
//   the view inside its buffer → byteStride ≥ one element → the count against the bytes of the
//   buffer (before any allocation) → the accessor's last element inside its view.
//
// All arithmetic on declared offsets, strides and counts is done so that it cannot overflow.
// Failures throw prt::Error("LABEL: WHAT: problem"), one line, LABEL being the file.
//
// Element i, component c lies at view.byteOffset + accessor.byteOffset + i · stride +
// c · componentSize, stride = byteStride or, when 0, the element size (tightly packed).
// Normalised integers map to floats as glTF §3.11: unsigned x / (2ⁿ − 1), signed
// max(x / (2ⁿ⁻¹ − 1), −1).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace prt::gltf {

/// The parts of a glTF document the accessor reader needs, whatever parsed it (tinygltf for
/// the mesh loader, nlohmann::json for the bake file, which maps its binary chunk instead of
/// copying it). Values as the file declares them: nothing here is checked yet.
struct Document {
  struct Accessor {
    int bufferView = -1;
    std::size_t byteOffset = 0;
    std::size_t count = 0;
    std::string type;  ///< "SCALAR", "VEC2" .. "MAT4" as the file spells it
    int componentType = 0;
    bool normalized = false;
    bool sparse = false;
  };
  struct BufferView {
    int buffer = -1;
    std::size_t byteOffset = 0;
    std::size_t byteLength = 0;
    std::size_t byteStride = 0;  ///< 0: tightly packed
  };
  std::vector<Accessor> accessors;
  std::vector<BufferView> bufferViews;
  std::vector<std::span<const unsigned char>> buffers;  ///< bytes that outlive the reader
};

/// The document of a model tinygltf parsed (its buffers stay in the model).
Document documentOf(const tinygltf::Model& model);
/// The document of a glTF JSON whose buffer 0 is `bin` (a GLB's binary chunk; other buffers,
/// which would need a uri, are empty). Throws prt::Error(label, ...) on an ill-formed
/// accessors / bufferViews array (a member of the wrong type, a negative or non-integer value).
Document documentOf(const nlohmann::json& gltf, std::span<const unsigned char> bin,
                    const std::string& label);

/// glTF component type codes (§3.6.2.2).
enum ComponentType : int {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
};

/// Bytes of one component of `componentType`; 0 for a code glTF does not define.
std::size_t componentSize(int componentType);

/// Where an accessor's elements lie, every bound already checked.
struct AccessorSpan {
  const unsigned char* data = nullptr;  ///< the first element
  std::size_t count = 0;                ///< elements
  std::size_t stride = 0;               ///< bytes from one element to the next
  int components = 0;                   ///< per element: 1 (SCALAR) .. 16 (MAT4)
  int componentType = 0;                ///< a ComponentType
  bool normalized = false;

  /// Bytes of one element (components × component size).
  std::size_t elementSize() const { return std::size_t(components) * componentSize(componentType); }
  /// Start of element i (i < count).
  const unsigned char* element(std::size_t i) const { return data + i * stride; }
};

/// Reads accessors of one parsed glTF model; `label` (the file) begins every error message.
class AccessorReader {
 public:
  AccessorReader(std::string label, Document document);

  /// The element count accessor `index` declares (only the index is checked; nothing is read),
  /// for checking a total against a limit before reading.
  std::size_t count(int index, const std::string& what) const;
  /// Components per element of accessor `index` (1 SCALAR, 2 VEC2, ...; index checked).
  int components(int index, const std::string& what) const;

  /// Accessor `index`, every reference and bound checked (the list in the file comment).
  AccessorSpan span(int index, const std::string& what) const;

  /// `components` floats per element from any component type: float as stored, normalised
  /// integers mapped to [0, 1] or [−1, 1], other integers converted. The accessor must have
  /// exactly `components` components.
  std::vector<float> floats(int index, int components, const std::string& what) const;

  /// Vertex indices: a SCALAR accessor of unsigned bytes, shorts or ints.
  std::vector<std::uint32_t> indices(int index, const std::string& what) const;

  /// Exactly `count` elements of `components` × `componentType`, not normalised (a file we wrote
  /// ourselves and read back in its one layout), copied as stored into T (whose size must be
  /// the component size).
  template <typename T>
  std::vector<T> exact(int index, int components, int componentType, std::size_t count,
                       const std::string& what) const {
    const AccessorSpan s = spanExact(index, components, componentType, count, what, sizeof(T));
    std::vector<T> out(s.count * std::size_t(s.components));
    const std::size_t elem = s.elementSize();
    for (std::size_t i = 0; i < s.count; ++i)
      std::memcpy(out.data() + i * std::size_t(s.components), s.element(i), elem);
    return out;
  }

  /// The span of exactly `count` elements of `components` × `componentType`, not normalised,
  /// every bound checked (what exact<T> copies; a caller may view it instead).
  AccessorSpan spanExact(int index, int components, int componentType, std::size_t count,
                         const std::string& what, std::size_t valueSize) const;

  /// The bytes of bufferView `index` (an embedded image's), the view checked to lie inside its
  /// buffer.
  std::span<const unsigned char> viewBytes(int index, const std::string& what) const;

  /// Throws prt::Error(label, msg).
  [[noreturn]] void fail(const std::string& msg) const;

 private:
  const Document::Accessor& accessorAt(int index, const std::string& what) const;

  std::string label_;
  Document doc_;
};

}  // namespace prt::gltf
