#include "prt/image/data_texture.hpp"

#include <png.h>
#include <tinyexr.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt::image {

namespace {

void checkSize(int width, int height, int channels, const std::string& name,
               int maxChannels = 4) {
  if (width < 1 || height < 1 || width > 65535 || height > 65535)
    throw Error(name, "a data texture of " + std::to_string(width) + " x " +
                          std::to_string(height) + " texels cannot be written");
  if (channels < 1 || channels > maxChannels)
    throw Error(name, "a data texture holds 1 to " + std::to_string(maxChannels) +
                          " channels, not " + std::to_string(channels));
}

void appendToString(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<char*>(data), length);
}

/// libpng reports errors by longjmp: this frame holds nothing with a destructor, so a jump
/// back to its setjmp leaks nothing. False on any libpng error.
bool writePng(std::string& out, int width, int height, int channels, const png_byte* rows,
              std::size_t rowBytes, int bitDepth = 16) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  static constexpr int kTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                   PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, &out, appendToString, nullptr);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), bitDepth, kTypes[channels - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, rows + std::size_t(y) * rowBytes);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::string encodeExrData(const DataTexture& t, const std::string& name) {
  const int n = static_cast<int>(std::min<std::size_t>(t.planes.size(), kMaxExrChannels + 1));
  checkSize(t.width, t.height, n, name, kMaxExrChannels);
  const std::size_t texels = std::size_t(t.width) * std::size_t(t.height);
  if (t.channelNames.size() != t.planes.size())
    throw Error(name, "data texture: the channel names do not match the planes");
  for (const auto& p : t.planes)
    if (p.size() != texels) throw Error(name, "data texture: a plane does not match the size");
  // EXR lists channels sorted by name; readers find them by name.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return t.channelNames[a] < t.channelNames[b]; });
  for (int k = 0; k < n; ++k)
    if (t.channelNames[order[k]].empty() || t.channelNames[order[k]].size() > 255 ||
        (k > 0 && t.channelNames[order[k]] == t.channelNames[order[k - 1]]))
      throw Error(name, "data texture: channel name '" + t.channelNames[order[k]] +
                            "' is empty, too long or not unique");
  std::vector<const float*> ptrs(n);
  std::vector<EXRChannelInfo> info(n);
  std::vector<int> types(n, TINYEXR_PIXELTYPE_FLOAT);
  for (int k = 0; k < n; ++k) {
    ptrs[k] = t.planes[order[k]].data();
    std::memset(&info[k], 0, sizeof(EXRChannelInfo));
    std::strncpy(info[k].name, t.channelNames[order[k]].c_str(), 255);
  }
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = n;
  image.images = reinterpret_cast<unsigned char**>(const_cast<float**>(ptrs.data()));
  image.width = t.width;
  image.height = t.height;
  header.num_channels = n;
  header.channels = info.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = types.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  // String attributes: EXR's "string" type, its bytes without a terminator.
  if (t.attributes.size() > TINYEXR_MAX_CUSTOM_ATTRIBUTES)
    throw Error(name, "data texture: more header attributes than OpenEXR files hold here");
  std::vector<EXRAttribute> attributes(t.attributes.size());
  for (std::size_t i = 0; i < t.attributes.size(); ++i) {
    const auto& [key, value] = t.attributes[i];
    if (key.empty() || key.size() > 255 || value.size() > (std::size_t(1) << 30))
      throw Error(name, "data texture: attribute '" + key.substr(0, 40) + "' cannot be written");
    std::memset(&attributes[i], 0, sizeof(EXRAttribute));
    std::strncpy(attributes[i].name, key.c_str(), 255);
    std::strncpy(attributes[i].type, "string", 255);
    attributes[i].size = int(value.size());
    attributes[i].value = reinterpret_cast<unsigned char*>(const_cast<char*>(value.data()));
  }
  header.num_custom_attributes = int(attributes.size());
  header.custom_attributes = attributes.empty() ? nullptr : attributes.data();
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0) {
    const std::string why = err ? err : "unknown reason";
    if (err) FreeEXRErrorMessage(err);
    throw Error(name, "cannot encode OpenEXR (" + why + ")");
  }
  std::string out(reinterpret_cast<char*>(memory), size);
  std::free(memory);
  return out;
}

std::string encodePng16(int width, int height, int channels, std::span<const std::uint16_t> values,
                        const std::string& name) {
  checkSize(width, height, channels, name);
  const std::size_t rowValues = std::size_t(width) * std::size_t(channels);
  if (values.size() != rowValues * std::size_t(height))
    throw Error(name, "16-bit PNG: the values do not match the size");
  // PNG stores 16-bit samples big-endian.
  std::vector<png_byte> bytes(values.size() * 2);
  for (std::size_t i = 0; i < values.size(); ++i) {
    bytes[2 * i] = png_byte(values[i] >> 8);
    bytes[2 * i + 1] = png_byte(values[i] & 0xff);
  }
  std::string out;
  if (!writePng(out, width, height, channels, bytes.data(), rowValues * 2))
    throw Error(name, "cannot encode PNG");
  return out;
}

std::string encodePng8(int width, int height, int channels, std::span<const std::uint8_t> values,
                       const std::string& name) {
  checkSize(width, height, channels, name);
  const std::size_t rowValues = std::size_t(width) * std::size_t(channels);
  if (values.size() != rowValues * std::size_t(height))
    throw Error(name, "8-bit PNG: the values do not match the size");
  std::string out;
  if (!writePng(out, width, height, channels, values.data(), rowValues, 8))
    throw Error(name, "cannot encode PNG");
  return out;
}

}  // namespace prt::image
