#include "prt/gltf/accessor.hpp"

#include <tiny_gltf.h>

#include <algorithm>

#include "prt/core/error.hpp"

namespace prt::gltf {

namespace {

/// The glTF `type` of an element of `components` components that we read: SCALAR or VECn.
int vectorType(int components) {
  return components == 1 ? TINYGLTF_TYPE_SCALAR : components;
}

std::string typeName(int type) {
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
  return "type " + std::to_string(type);
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

AccessorReader::AccessorReader(std::string label, const tinygltf::Model& model)
    : label_(std::move(label)), model_(model) {}

void AccessorReader::fail(const std::string& msg) const {
  throw Error(label_, msg);
}

namespace {

const tinygltf::Accessor& accessorAt(const AccessorReader& r, const tinygltf::Model& m, int index,
                                     const std::string& what) {
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    r.fail(what + ": accessor " + std::to_string(index) + " does not exist (the file has " +
           std::to_string(m.accessors.size()) + ")");
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  if (a.sparse.isSparse) r.fail(what + ": sparse accessors are not supported");
  return a;
}

}  // namespace

std::size_t AccessorReader::count(int index, const std::string& what) const {
  return accessorAt(*this, model_, index, what).count;
}

int AccessorReader::components(int index, const std::string& what) const {
  const tinygltf::Accessor& a = accessorAt(*this, model_, index, what);
  const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (comps <= 0)
    fail(what + ": accessor " + std::to_string(index) + " has an invalid " + typeName(a.type));
  return comps;
}

AccessorSpan AccessorReader::span(int index, const std::string& what) const {
  const tinygltf::Accessor& a = accessorAt(*this, model_, index, what);
  const std::string acc = "accessor " + std::to_string(index);
  AccessorSpan s;
  s.components = components(index, what);
  s.componentType = a.componentType;
  s.normalized = a.normalized;
  const std::size_t csize = componentSize(a.componentType);
  if (csize == 0) fail(what + ": " + acc + " has an invalid " + componentName(a.componentType));
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= model_.bufferViews.size())
    fail(what + ": " + acc + " has no valid bufferView");
  const std::string view = "bufferView " + std::to_string(a.bufferView);
  const tinygltf::BufferView& v = model_.bufferViews[std::size_t(a.bufferView)];
  if (v.buffer < 0 || std::size_t(v.buffer) >= model_.buffers.size())
    fail(what + ": " + view + " has no valid buffer");
  const std::vector<unsigned char>& buf = model_.buffers[std::size_t(v.buffer)].data;
  // Offsets, lengths, strides and counts come from the file: every comparison below is written
  // so that it cannot overflow (subtract from a bound already checked, or divide).
  if (v.byteOffset > buf.size() || v.byteLength > buf.size() - v.byteOffset)
    fail(what + ": " + view + " (" + std::to_string(v.byteLength) + " bytes at " +
         std::to_string(v.byteOffset) + ") lies outside its buffer of " +
         std::to_string(buf.size()) + " bytes (truncated file?)");
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
  s.data = buf.data() + v.byteOffset + a.byteOffset;
  s.count = n;
  s.stride = stride;
  return s;
}

std::vector<float> AccessorReader::floats(int index, int want, const std::string& what) const {
  const AccessorSpan s = span(index, what);  // checks the index
  const int type = model_.accessors[std::size_t(index)].type;
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
  if (model_.accessors[std::size_t(index)].type != TINYGLTF_TYPE_SCALAR)
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
  const tinygltf::Accessor& a = accessorAt(*this, model_, index, what);
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
