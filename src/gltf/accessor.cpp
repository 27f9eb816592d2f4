#include "prt/gltf/accessor.hpp"

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <limits>

#include "prt/core/error.hpp"

namespace prt::gltf {

namespace {

/// The glTF `type` of an element of `components` components that we read: SCALAR or VECn.
std::string vectorType(int components) {
  return components == 1 ? "SCALAR" : "VEC" + std::to_string(components);
}

/// Components of a glTF element type; 0 for a name glTF does not define.
int componentsOf(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

std::string typeName(const std::string& type) {
  return componentsOf(type) ? type : "type '" + type.substr(0, 40) + "'";
}

/// tinygltf's type code as glTF's name.
std::string tinygltfType(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
  }
  return "code " + std::to_string(type);
}

std::string componentName(int componentType) {
  switch (componentType) {
    case kByte:
      return "BYTE";
    case kUnsignedByte:
      return "UNSIGNED_BYTE";
    case kShort:
      return "SHORT";
    case kUnsignedShort:
      return "UNSIGNED_SHORT";
    case kUnsignedInt:
      return "UNSIGNED_INT";
    case kFloat:
      return "FLOAT";
  }
  return "component type " + std::to_string(componentType);
}

/// One component at p as a float; normalised integers per glTF §3.11.
float component(const unsigned char* p, int type, bool normalise) {
  switch (type) {
    case kFloat: {
      float x;
      std::memcpy(&x, p, 4);
      return x;
    }
    case kUnsignedByte:
      return normalise ? p[0] / 255.0f : p[0];
    case kByte: {
      std::int8_t x;
      std::memcpy(&x, p, 1);
      return normalise ? std::max(x / 127.0f, -1.0f) : x;
    }
    case kUnsignedShort: {
      std::uint16_t x;
      std::memcpy(&x, p, 2);
      return normalise ? x / 65535.0f : x;
    }
    case kShort: {
      std::int16_t x;
      std::memcpy(&x, p, 2);
      return normalise ? std::max(x / 32767.0f, -1.0f) : x;
    }
    case kUnsignedInt: {  // glTF allows no normalised 32-bit integers
      std::uint32_t x;
      std::memcpy(&x, p, 4);
      return float(x);
    }
  }
  return 0;
}

}  // namespace

std::size_t componentSize(int componentType) {
  switch (componentType) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
  }
  return 0;
}

Document documentOf(const tinygltf::Model& model) {
  Document d;
  for (const tinygltf::Accessor& a : model.accessors) {
    Document::Accessor x;
    x.bufferView = a.bufferView;
    x.byteOffset = a.byteOffset;
    x.count = a.count;
    x.type = tinygltfType(a.type);
    x.componentType = a.componentType;
    x.normalized = a.normalized;
    x.sparse = a.sparse.isSparse;
    d.accessors.push_back(std::move(x));
  }
  for (const tinygltf::BufferView& v : model.bufferViews)
    d.bufferViews.push_back({v.buffer, v.byteOffset, v.byteLength, v.byteStride});
  for (const tinygltf::Buffer& b : model.buffers) d.buffers.emplace_back(b.data);
  return d;
}

Document documentOf(const nlohmann::json& gltf, std::span<const unsigned char> bin,
                    const std::string& label) {
  using nlohmann::json;
  // A member read as the type glTF gives it; absent members keep their default.
  const auto integer = [&](const json& o, const char* key, std::size_t fallback,
                           const std::string& where) -> std::size_t {
    if (!o.contains(key)) return fallback;
    const json& v = o[key];
    if (!v.is_number_unsigned())
      throw Error(label, where + "." + key + " is not a non-negative integer");
    return v.get<std::size_t>();
  };
  const auto index = [&](const json& o, const char* key, const std::string& where) -> int {
    const std::size_t i = integer(o, key, std::size_t(-1), where);
    return i > std::size_t(std::numeric_limits<int>::max()) ? -1 : static_cast<int>(i);
  };
  const auto array = [&](const char* key) -> const json& {
    static const json empty = json::array();
    if (!gltf.contains(key)) return empty;
    if (!gltf[key].is_array()) throw Error(label, std::string(key) + " is not an array");
    return gltf[key];
  };
  Document d;
  const json& accessors = array("accessors");
  for (std::size_t i = 0; i < accessors.size(); ++i) {
    const json& a = accessors[i];
    const std::string where = "accessors[" + std::to_string(i) + "]";
    if (!a.is_object()) throw Error(label, where + " is not an object");
    Document::Accessor x;
    x.bufferView = index(a, "bufferView", where);
    x.byteOffset = integer(a, "byteOffset", 0, where);
    x.count = integer(a, "count", 0, where);
    x.componentType = static_cast<int>(integer(a, "componentType", 0, where));
    if (a.contains("type")) {
      if (!a["type"].is_string()) throw Error(label, where + ".type is not a string");
      x.type = a["type"].get<std::string>();
    }
    if (a.contains("normalized")) {
      if (!a["normalized"].is_boolean()) throw Error(label, where + ".normalized is not a boolean");
      x.normalized = a["normalized"].get<bool>();
    }
    x.sparse = a.contains("sparse");
    d.accessors.push_back(std::move(x));
  }
  const json& views = array("bufferViews");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const json& v = views[i];
    const std::string where = "bufferViews[" + std::to_string(i) + "]";
    if (!v.is_object()) throw Error(label, where + " is not an object");
    d.bufferViews.push_back({index(v, "buffer", where), integer(v, "byteOffset", 0, where),
                             integer(v, "byteLength", 0, where),
                             integer(v, "byteStride", 0, where)});
  }
  const json& buffers = array("buffers");
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (i > 0 || (buffers[i].is_object() && buffers[i].contains("uri")))
      d.buffers.emplace_back();  // not the binary chunk: no bytes (a bake never refers out)
    else
      d.buffers.push_back(bin.first(
          std::min<std::size_t>(bin.size(), integer(buffers[i], "byteLength", 0, "buffers[0]"))));
  }
  return d;
}

AccessorReader::AccessorReader(std::string label, Document document)
    : label_(std::move(label)), doc_(std::move(document)) {}

void AccessorReader::fail(const std::string& msg) const {
  throw Error(label_, msg);
}

const Document::Accessor& AccessorReader::accessorAt(int index, const std::string& what) const {
  if (index < 0 || std::size_t(index) >= doc_.accessors.size())
    fail(what + ": accessor " + std::to_string(index) + " does not exist (the file has " +
         std::to_string(doc_.accessors.size()) + ")");
  const Document::Accessor& a = doc_.accessors[std::size_t(index)];
  if (a.sparse) fail(what + ": sparse accessors are not supported");
  return a;
}

std::size_t AccessorReader::count(int index, const std::string& what) const {
  return accessorAt(index, what).count;
}

int AccessorReader::components(int index, const std::string& what) const {
  const Document::Accessor& a = accessorAt(index, what);
  const int comps = componentsOf(a.type);
  if (comps <= 0)
    fail(what + ": accessor " + std::to_string(index) + " has an invalid " + typeName(a.type));
  return comps;
}

AccessorSpan AccessorReader::span(int index, const std::string& what) const {
  const Document::Accessor& a = accessorAt(index, what);
  const std::string acc = "accessor " + std::to_string(index);
  AccessorSpan s;
  s.components = components(index, what);
  s.componentType = a.componentType;
  s.normalized = a.normalized;
  const std::size_t csize = componentSize(a.componentType);
  if (csize == 0) fail(what + ": " + acc + " has an invalid " + componentName(a.componentType));
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= doc_.bufferViews.size())
    fail(what + ": " + acc + " has no valid bufferView");
  const std::string view = "bufferView " + std::to_string(a.bufferView);
  // The view's bytes, checked to lie inside their buffer (viewBytes). Offsets, lengths, strides
  // and counts come from the file: every comparison below is written so that it cannot overflow
  // (subtract from a bound already checked, or divide).
  const std::span<const unsigned char> bytes = viewBytes(a.bufferView, what);
  const Document::BufferView& v = doc_.bufferViews[std::size_t(a.bufferView)];
  const std::span<const unsigned char> buf = doc_.buffers[std::size_t(v.buffer)];
  const std::size_t elem = csize * std::size_t(s.components);
  const std::size_t stride = v.byteStride ? v.byteStride : elem;
  if (stride < elem)
    fail(what + ": byteStride " + std::to_string(stride) + " is smaller than an element (" +
         std::to_string(elem) + " bytes)");
  // Every element takes at least one byte: a count beyond the buffer's bytes is refused before
  // anything is allocated for it.
  const std::size_t n = a.count;
  if (n > buf.size())
    fail(what + ": accessor count " + std::to_string(n) + " exceeds the " +
         std::to_string(buf.size()) + " bytes of its buffer");
  const std::size_t len = v.byteLength;
  if (n > 0 && (a.byteOffset > len || (n - 1) > (len - a.byteOffset) / stride ||
                elem > len - a.byteOffset - (n - 1) * stride))
    fail(what + ": " + acc + " (" + std::to_string(n) + " elements of " + std::to_string(elem) +
         " bytes, stride " + std::to_string(stride) + ", at " + std::to_string(a.byteOffset) +
         ") runs past the end of its " + view + " (" + std::to_string(len) +
         " bytes; truncated file?)");
  s.data = bytes.data() + a.byteOffset;
  s.count = n;
  s.stride = stride;
  return s;
}

std::span<const unsigned char> AccessorReader::viewBytes(int index, const std::string& what) const {
  if (index < 0 || std::size_t(index) >= doc_.bufferViews.size())
    fail(what + ": bufferView " + std::to_string(index) + " does not exist (the file has " +
         std::to_string(doc_.bufferViews.size()) + ")");
  const std::string view = "bufferView " + std::to_string(index);
  const Document::BufferView& v = doc_.bufferViews[std::size_t(index)];
  if (v.buffer < 0 || std::size_t(v.buffer) >= doc_.buffers.size())
    fail(what + ": " + view + " has no valid buffer");
  const std::span<const unsigned char> buf = doc_.buffers[std::size_t(v.buffer)];
  if (v.byteOffset > buf.size() || v.byteLength > buf.size() - v.byteOffset)
    fail(what + ": " + view + " (" + std::to_string(v.byteLength) + " bytes at " +
         std::to_string(v.byteOffset) + ") lies outside its buffer of " +
         std::to_string(buf.size()) + " bytes (truncated file?)");
  return buf.subspan(v.byteOffset, v.byteLength);
}

std::vector<float> AccessorReader::floats(int index, int want, const std::string& what) const {
  const AccessorSpan s = span(index, what);  // checks the index
  const std::string& type = doc_.accessors[std::size_t(index)].type;
  if (s.components != want || type != vectorType(want))
    fail(what + " has " + std::to_string(s.components) + " components (" + typeName(type) +
         "), expected " + std::to_string(want) + " (" + typeName(vectorType(want)) + ")");
  const std::size_t csize = componentSize(s.componentType);
  // Float data is never normalised; integers are when the accessor says so.
  const bool normalise = s.normalized || s.componentType == kFloat;
  std::vector<float> out(s.count * std::size_t(want));
  for (std::size_t i = 0; i < s.count; ++i)
    for (int c = 0; c < want; ++c)
      out[i * std::size_t(want) + std::size_t(c)] =
          component(s.element(i) + std::size_t(c) * csize, s.componentType, normalise);
  return out;
}

std::vector<std::uint32_t> AccessorReader::indices(int index, const std::string& what) const {
  const AccessorSpan s = span(index, what);
  if (doc_.accessors[std::size_t(index)].type != "SCALAR")
    fail(what + ": accessor " + std::to_string(index) + " is not SCALAR");
  std::vector<std::uint32_t> out(s.count);
  for (std::size_t i = 0; i < s.count; ++i) {
    const unsigned char* p = s.element(i);
    switch (s.componentType) {
      case kUnsignedByte:
        out[i] = p[0];
        break;
      case kUnsignedShort: {
        std::uint16_t x;
        std::memcpy(&x, p, 2);
        out[i] = x;
        break;
      }
      case kUnsignedInt: {
        std::uint32_t x;
        std::memcpy(&x, p, 4);
        out[i] = x;
        break;
      }
      default:
        fail(what + ": " + componentName(s.componentType) +
             " is not an unsigned integer component type");
    }
  }
  return out;
}

AccessorSpan AccessorReader::spanExact(int index, int components, int componentType,
                                       std::size_t count, const std::string& what,
                                       std::size_t valueSize) const {
  PRT_CHECK(valueSize == componentSize(componentType), "exact<T>: T does not fit the component");
  const Document::Accessor& a = accessorAt(index, what);
  const std::string acc = "accessor " + std::to_string(index);
  if (a.type != vectorType(components) || a.componentType != componentType || a.normalized)
    fail(what + ": " + acc + " is " + typeName(a.type) + " of " + componentName(a.componentType) +
         (a.normalized ? " (normalized)" : "") + ", expected " + typeName(vectorType(components)) +
         " of " + componentName(componentType));
  if (a.count != count)
    fail(what + ": " + acc + " has " + std::to_string(a.count) + " elements, expected " +
         std::to_string(count));
  return span(index, what);
}

}  // namespace prt::gltf
