#include "prt/image/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"

namespace prt::image {

namespace {

// stb reads through callbacks so we notice truncation: stb_image pads a short file with zeros
// instead of failing for some formats (Radiance RGBE, baseline JPEG), so a read asked for after
// the last byte means the file ended before the decoder was done.
struct MemoryReader {
  const unsigned char* data;
  std::size_t size;
  std::size_t pos = 0;
  bool readPastEnd = false;
};

int readCallback(void* user, char* out, int n) {
  auto* r = static_cast<MemoryReader*>(user);
  const std::size_t left = r->size - r->pos;
  const std::size_t k = std::min<std::size_t>(left, static_cast<std::size_t>(std::max(n, 0)));
  if (k == 0 && n > 0) r->readPastEnd = true;
  std::memcpy(out, r->data + r->pos, k);
  r->pos += k;
  return static_cast<int>(k);
}
void skipCallback(void* user, int n) {
  auto* r = static_cast<MemoryReader*>(user);
  if (n < 0) {
    r->pos -= std::min<std::size_t>(r->pos, static_cast<std::size_t>(-n));
  } else {
    r->pos = std::min(r->size, r->pos + static_cast<std::size_t>(n));
  }
}
int eofCallback(void* user) {
  auto* r = static_cast<MemoryReader*>(user);
  return r->pos >= r->size ? 1 : 0;
}
const stbi_io_callbacks kCallbacks{readCallback, skipCallback, eofCallback};

std::string stbReason() {
  const char* why = stbi_failure_reason();
  return why ? why : "unknown reason";
}

// Radiance RGBE (Ward, "Real Pixels", Graphics Gems II, 1991), decoded here with bounds checks
// on every byte: stb_image loops forever on some truncated run-length scan lines.
// Supports the "-Y H +X W" orientation (what every writer emits), flat and new-style RLE scan
// lines. Decoding follows Radiance's colr_color: (m + 0.5) · 2^(e − 136), 0 when e = 0.
Image readRadianceHdr(const std::string& path, std::span<const unsigned char> b) {
  std::size_t pos = 0;
  auto line = [&]() -> std::string {
    std::string out;
    while (pos < b.size() && b[pos] != '\n') out += static_cast<char>(b[pos++]);
    if (pos >= b.size()) throw Error(path, "truncated Radiance HDR header");
    ++pos;
    return out;
  };
  const std::string magic = line();
  if (magic != "#?RADIANCE" && magic != "#?RGBE")
    throw Error(path, "not a Radiance HDR file (bad signature)");
  for (std::string l = line(); !l.empty(); l = line())
    if (l.rfind("FORMAT=", 0) == 0 && l != "FORMAT=32-bit_rle_rgbe")
      throw Error(path, "unsupported Radiance pixel format '" + l.substr(7) + "'");
  const std::string res = line();
  int w = 0, h = 0;
  char ya[3] = {}, xa[3] = {};
  if (std::sscanf(res.c_str(), "%2s %d %2s %d", ya, &h, xa, &w) != 4 || std::string(ya) != "-Y" ||
      std::string(xa) != "+X" || w <= 0 || h <= 0 || w > (1 << 16) || h > (1 << 16))
    throw Error(path, "unsupported Radiance resolution line '" + res.substr(0, 60) +
                          "' (expected -Y H +X W)");
  checkImageSize(path, std::uint64_t(w), std::uint64_t(h));
  // The fewest bytes a scan line can take: flat 4w, or run-length encoded 4 header bytes plus, per
  // channel, one (count, value) pair per run of at most 127. Check before allocating.
  {
    const std::uint64_t runs = (std::uint64_t(w) + 126) / 127;
    const std::uint64_t minLine = (w >= 8 && w < 32768)
                                      ? std::min<std::uint64_t>(4ull * w, 4 + 8 * runs)
                                      : 4ull * std::uint64_t(w);
    if (std::uint64_t(h) * minLine > b.size() - pos)
      throw Error(path, "truncated Radiance HDR file (" + std::to_string(w) + "x" +
                            std::to_string(h) + " needs at least " +
                            std::to_string(std::uint64_t(h) * minLine) + " bytes of pixels, " +
                            std::to_string(b.size() - pos) + " present)");
  }
  Image img(w, h);
  std::vector<unsigned char> scan(static_cast<std::size_t>(w) * 4);
  auto need = [&](std::size_t n) {
    if (pos + n > b.size())
      throw Error(path, "truncated Radiance HDR file (pixel data ends early)");
  };
  for (int y = 0; y < h; ++y) {
    need(4);
    // As Radiance's freadcolrs: a scan line of a width in [8, 32767] that starts 2, 2, c (c < 128)
    // is run-length encoded and must declare the image's width; another width is a corrupt file
    // (Radiance rejects it), not flat pixels to decode as garbage.
    const bool rle = w >= 8 && w < 32768 && b[pos] == 2 && b[pos + 1] == 2 && b[pos + 2] < 128;
    if (rle && ((b[pos + 2] << 8) | b[pos + 3]) != w)
      throw Error(path, "corrupt Radiance HDR file: scan line " + std::to_string(y) +
                            " is run-length encoded for width " +
                            std::to_string((b[pos + 2] << 8) | b[pos + 3]) + ", the image is " +
                            std::to_string(w) + " wide");
    if (rle) {
      pos += 4;
      for (int c = 0; c < 4; ++c) {
        for (int x = 0; x < w;) {
          need(1);
          int count = b[pos++];
          if (count > 128) {
            count -= 128;
            need(1);
            if (x + count > w) throw Error(path, "corrupt Radiance run length");
            const unsigned char v = b[pos++];
            for (int i = 0; i < count; ++i) scan[4 * (x++) + c] = v;
          } else {
            if (count == 0 || x + count > w) throw Error(path, "corrupt Radiance run length");
            need(count);
            for (int i = 0; i < count; ++i) scan[4 * (x++) + c] = b[pos++];
          }
        }
      }
    } else {
      need(static_cast<std::size_t>(w) * 4);
      std::copy_n(b.data() + pos, std::size_t(w) * 4, scan.begin());
      pos += static_cast<std::size_t>(w) * 4;
    }
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = &scan[4 * x];
      if (p[3] == 0) {
        img.at(x, y) = Rgb(0.0f);
      } else {
        const float f = std::ldexp(1.0f, static_cast<int>(p[3]) - 136);
        img.at(x, y) = {(p[0] + 0.5f) * f, (p[1] + 0.5f) * f, (p[2] + 0.5f) * f};
      }
    }
  }
  return img;
}

// JPEG streams end with an EOI marker (FF D9); stb_image decodes a cut-off JPEG without error.
bool jpegComplete(std::span<const unsigned char> b) {
  std::size_t end = b.size();
  while (end > 2 && b[end - 1] == 0) --end;  // some writers pad after EOI
  return end >= 4 && b[end - 2] == 0xFF && b[end - 1] == 0xD9;
}

bool isPng(std::span<const unsigned char> b) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return b.size() >= 8 && std::memcmp(b.data(), sig, 8) == 0;
}
bool isJpeg(std::span<const unsigned char> b) {
  return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

// stb_image grows its buffer to a chunk's declared length before reading it (a 104-byte PNG
// declaring a 1.7 GB IDAT, found by fuzz_ldr): every chunk must fit in the bytes present.
void checkPngChunks(const std::string& path, std::span<const unsigned char> b) {
  std::size_t pos = 8;
  while (b.size() - pos >= 12) {
    const std::uint32_t len =
        (std::uint32_t(b[pos]) << 24) | (b[pos + 1] << 16) | (b[pos + 2] << 8) | b[pos + 3];
    const std::string type(reinterpret_cast<const char*>(b.data() + pos + 4), 4);
    if (len > b.size() - pos - 12)
      throw Error(path, "truncated or corrupt PNG: a chunk declares " + std::to_string(len) +
                            " bytes, " + std::to_string(b.size() - pos - 12) + " remain");
    pos += 12 + std::size_t(len);
    if (type == "IEND") return;
  }
}

/// The checks before stb_image sees PNG or JPEG bytes; true for a JPEG. Decode by content (a PNG
/// named .jpg still reads), but only PNG and JPEG: stb_image would also take GIF, PSD, PIC, PNM,
/// TGA and HDR data under these names. `expected` names the format for the bad-signature error.
bool checkStbInput(const std::string& path, std::span<const unsigned char> bytes,
                   const std::string& expected) {
  const bool png = isPng(bytes), jpeg = isJpeg(bytes);
  if (!png && !jpeg) throw Error(path, "not a " + expected + " (bad signature)");
  if (png) checkPngChunks(path, bytes);
  if (jpeg && !jpegComplete(bytes))
    throw Error(path, "truncated JPEG file (no end-of-image marker)");
  checkEncodedImageSize(path, bytes);
  return jpeg;
}

Image readStbLdr(const std::string& path, std::span<const unsigned char> bytes, LdrDecode decode,
                 bool jpegByName) {
  const bool jpeg = checkStbInput(path, bytes, jpegByName ? "JPEG file" : "PNG file");
  MemoryReader reader{bytes.data(), bytes.size()};
  const bool sixteen =
      !jpeg && stbi_is_16_bit_from_memory(bytes.data(), static_cast<int>(bytes.size()));
  int w = 0, h = 0, n = 0;
  Image img;
  if (sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> data(
        stbi_load_16_from_callbacks(&kCallbacks, &reader, &w, &h, &n, 3), stbi_image_free);
    if (!data) throw Error(path, "cannot decode image (" + stbReason() + ")");
    img = Image(w, h);
    for (std::size_t i = 0; i < 3 * img.size(); ++i) {
      const float v = static_cast<float>(data.get()[i]) / 65535.0f;
      (&img.pixels[i / 3].x)[i % 3] = decode == LdrDecode::Srgb
                                          ? srgbToLinear(v)
                                          : static_cast<float>(std::pow(double(v), double(2.2f)));
    }
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> data(
        stbi_load_from_callbacks(&kCallbacks, &reader, &w, &h, &n, 3), stbi_image_free);
    if (!data) throw Error(path, "cannot decode image (" + stbReason() + ")");
    img = Image(w, h);
    for (std::size_t i = 0; i < 3 * img.size(); ++i) {
      const std::uint8_t v = data.get()[i];
      (&img.pixels[i / 3].x)[i % 3] =
          decode == LdrDecode::Srgb ? srgb8ToLinear(v) : gamma22ToLinear(v);
    }
  }
  if (reader.readPastEnd) throw Error(path, "truncated image file");
  return img;
}

// The file's bytes (already read and checked) as an OpenEXR input stream, so the library decodes
// exactly what was read, without opening the file a second time. Reads past the end throw, as
// the library expects of a truncated file.
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const std::string& name, std::span<const unsigned char> bytes)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    // pos_ may be anything a corrupt offset table seeks to: compare without overflowing.
    if (n < 0 || pos_ > bytes_.size() || static_cast<std::uint64_t>(n) > bytes_.size() - pos_)
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::uint64_t>(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }

 private:
  std::span<const unsigned char> bytes_;
  std::uint64_t pos_ = 0;
};

// The OpenEXR library: every compression (DWAA/DWAB included), tiled or scan-line files.
Image readOpenExr(const std::string& path, std::span<const unsigned char> bytes) {
  try {
    // The library checks the header's data window (and tile size) against these before it
    // allocates anything sized by them; 0 would mean "no limit".
    const Limits lim = limits();
    const int side = int(std::min<std::uint64_t>(lim.maxImageSide, 1u << 30));
    Imf::Header::setMaxImageSize(side, side);
    Imf::Header::setMaxTileSize(side, side);
    MemoryIStream stream(path, bytes);
    Imf::InputFile file(stream);
    const Imath::Box2i dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    if (w <= 0 || h <= 0) throw Error(path, "empty OpenEXR data window");
    checkImageSize(path, std::uint64_t(w), std::uint64_t(h));
    const Imf::ChannelList& channels = file.header().channels();
    const bool rgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    const bool grey = !rgb && channels.findChannel("Y");
    if (!rgb && !grey) throw Error(path, "OpenEXR file has neither R, G, B nor Y channels");
    std::vector<float> planes(static_cast<std::size_t>(w) * h * 3, 0.0f);
    Imf::FrameBuffer fb;
    const std::size_t xs = sizeof(float) * 3, ys = xs * static_cast<std::size_t>(w);
    // Slice::Make points the slice at the data window's origin with integer arithmetic (the
    // classic "base - origin" pointer leaves the array, undefined behaviour UBSan reports).
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      fb.insert(grey ? "Y" : names[c],
                Imf::Slice::Make(Imf::FLOAT, planes.data() + c, dw, xs, ys, 1, 1, 0.0));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    Image img(w, h);
    for (std::size_t i = 0; i < img.size(); ++i)
      img.pixels[i] = {planes[3 * i], planes[3 * i + 1], planes[3 * i + 2]};
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    std::string what = e.what();
    if (auto nl = what.find('\n'); nl != std::string::npos) what.resize(nl);
    throw Error(path, "cannot read OpenEXR file (" + what + ")");
  }
}

// OpenEXR allocates what the header declares before reading it: an attribute's size (1.8 GB for
// an unknown attribute type, found by fuzz_exr), a preview image's width × height, the chunk
// offset table of a data window cut into tiny tiles. Walk the header first (OpenEXR file layout:
// magic, version, then per part NUL-terminated name, type, int32 size, value; an empty name ends
// a header, and in a multi-part file an empty header ends the list) and check every declared
// size against the bytes present and the image limits.
/// Bytes OpenEXR reads for a value of a fixed-size attribute type (0: variable or unknown).
std::size_t exrFixedSize(const std::string& type) {
  static const std::pair<const char*, std::size_t> table[] = {
      {"box2i", 16},      {"box2f", 16},   {"chromaticities", 32},
      {"compression", 1}, {"double", 8},   {"envmap", 1},
      {"float", 4},       {"int", 4},      {"keycode", 28},
      {"lineOrder", 1},   {"m33f", 36},    {"m33d", 72},
      {"m44f", 64},       {"m44d", 128},   {"rational", 8},
      {"tiledesc", 9},    {"timecode", 8}, {"v2i", 8},
      {"v2f", 8},         {"v2d", 16},     {"v3i", 12},
      {"v3f", 12},        {"v3d", 24},     {"deepImageState", 1}};
  for (const auto& [name, size] : table)
    if (type == name) return size;
  return 0;
}

void checkExrHeader(const std::string& path, std::span<const unsigned char> b) {
  std::size_t pos = 8;
  if (b.size() < 8) throw Error(path, "truncated OpenEXR header");
  const std::uint32_t version = b[4] | (b[5] << 8) | (b[6] << 16) | (std::uint32_t(b[7]) << 24);
  const bool multipart = version & 0x1000;
  const auto cstr = [&](const char* what) {
    const std::size_t start = pos;
    while (pos < b.size() && b[pos] != 0) {
      if (pos - start > 255)
        throw Error(path, std::string("OpenEXR header: ") + what + " too long");
      ++pos;
    }
    if (pos >= b.size()) throw Error(path, "truncated OpenEXR header");
    ++pos;
    return std::string(reinterpret_cast<const char*>(b.data() + start), pos - 1 - start);
  };
  const auto i32 = [&](std::size_t at) {
    std::int32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  while (true) {
    std::int64_t w = 0, h = 0, tileX = 0, tileY = 0;
    bool haveWindow = false;
    while (true) {
      const std::string name = cstr("attribute name");
      if (name.empty()) break;
      const std::string type = cstr("attribute type");
      if (b.size() - pos < 4) throw Error(path, "truncated OpenEXR header");
      const std::int32_t size = i32(pos);
      pos += 4;
      if (size < 0 || std::size_t(size) > b.size() - pos)
        throw Error(path, "OpenEXR header: attribute '" + name.substr(0, 40) + "' declares " +
                              std::to_string(size) + " bytes, " + std::to_string(b.size() - pos) +
                              " remain (truncated or corrupt)");
      const std::size_t at = pos;
      // OpenEXR reads a known type's value by its own layout, not by the declared size, and
      // carries on from where that read stops: compute that layout too.
      std::size_t used = std::size_t(size);
      if (const std::size_t fixed = exrFixedSize(type)) {
        used = fixed;
      } else if (type == "chlist") {
        std::size_t p = at;
        while (true) {
          if (p >= b.size()) throw Error(path, "truncated OpenEXR header");
          const std::size_t nameStart = p;
          while (p < b.size() && b[p] != 0) ++p;
          if (p >= b.size() || p - nameStart > 255)
            throw Error(path, "corrupt OpenEXR channel list");
          ++p;
          if (p == nameStart + 1) break;  // empty name: end of the list
          if (b.size() - p < 16) throw Error(path, "truncated OpenEXR header");
          p += 16;
        }
        used = p - at;
      } else if (type == "preview") {
        if (size < 8) throw Error(path, "corrupt OpenEXR preview attribute");
        const std::uint64_t pw = std::uint32_t(i32(at)), ph = std::uint32_t(i32(at + 4));
        if (pw * ph * 4 != std::uint64_t(size) - 8)
          throw Error(path, "OpenEXR header: preview image " + std::to_string(pw) + "x" +
                                std::to_string(ph) + " does not fit its attribute");
      } else if (type == "stringvector") {
        for (std::size_t p = at; p < at + std::size_t(size);) {
          if (at + std::size_t(size) - p < 4) throw Error(path, "corrupt OpenEXR string vector");
          const std::int32_t len = i32(p);
          p += 4;
          if (len < 0 || std::size_t(len) > at + std::size_t(size) - p)
            throw Error(path, "corrupt OpenEXR string vector");
          p += std::size_t(len);
        }
      }
      // Valid files agree with themselves; refusing any disagreement makes our walk and
      // OpenEXR's the same whichever of the two sizes OpenEXR follows.
      if (used != std::size_t(size))
        throw Error(path, "OpenEXR header: attribute '" + name.substr(0, 40) + "' of type " +
                              type.substr(0, 40) + " declares " + std::to_string(size) +
                              " bytes but its value takes " + std::to_string(used));
      pos = at + used;
      if (type == "box2i" && name == "dataWindow") {
        w = std::int64_t(i32(at + 8)) - i32(at) + 1;
        h = std::int64_t(i32(at + 12)) - i32(at + 4) + 1;
        haveWindow = true;
      } else if (type == "tiledesc") {
        tileX = std::uint32_t(i32(at));
        tileY = std::uint32_t(i32(at + 4));
      } else if (name == "chunkCount" && type == "int") {
        const std::int32_t chunks = i32(at);
        if (chunks < 0 || std::uint64_t(chunks) * 8 > b.size())
          throw Error(path, "OpenEXR header: chunkCount " + std::to_string(chunks) +
                                " does not fit the file");
      }
    }
    if (haveWindow) {
      if (w <= 0 || h <= 0) throw Error(path, "empty OpenEXR data window");
      checkImageSize(path, std::uint64_t(w), std::uint64_t(h));
      // The chunk offset table (8 bytes per chunk) must be in the file: at most 256 scan lines
      // per chunk (DWAB), or the level-0 tiles of a tiled part.
      std::uint64_t chunks = std::uint64_t(h + 255) / 256;
      if (tileX > 0 && tileY > 0)
        chunks = std::uint64_t((w + tileX - 1) / tileX) * std::uint64_t((h + tileY - 1) / tileY);
      if (chunks > b.size() / 8)
        throw Error(path, "truncated OpenEXR file (" + std::to_string(w) + "x" + std::to_string(h) +
                              " needs " + std::to_string(chunks) + " chunk offsets)");
    }
    if (!multipart) break;
    if (pos >= b.size()) throw Error(path, "truncated OpenEXR header");
    if (b[pos] == 0) break;  // the empty header that ends a multi-part list
  }
}

Image readExr(const std::string& path, std::span<const unsigned char> bytes) {
  if (bytes.size() < 4 ||
      !(bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 && bytes[3] == 0x01))
    throw Error(path, "not an OpenEXR file (bad magic number)");
  checkExrHeader(path, bytes);
  // Read by the reference library: every compression (tinyexr lacks DWAA/DWAB, which Blender's
  // Poly Haven maps use) and, under AddressSanitizer, no leaks on malformed files (tinyexr's
  // decoder leaks its line buffers when a file is truncated). tinyexr writes our EXRs.
  return readOpenExr(path, bytes);
}

}  // namespace

bool isReadableImageExtension(const std::string& ext) {
  return ext == "hdr" || ext == "exr" || ext == "png" || ext == "jpg" || ext == "jpeg";
}

ReadStats sanitize(Image& img) {
  ReadStats s;
  for (Rgb& p : img.pixels) {
    bool nonFinite = false, negative = false;
    for (int c = 0; c < 3; ++c) {
      float& v = (&p.x)[c];
      if (!std::isfinite(v)) {
        v = 0.0f;
        nonFinite = true;
      } else if (v < 0.0f) {
        s.negativeSum -= v;
        v = 0.0f;
        negative = true;
      } else {
        s.positiveSum += v;
      }
    }
    s.nonFinitePixels += nonFinite;
    s.negativePixels += negative;
  }
  s.pixels = img.pixels.size();
  return s;
}

Image readImage(const std::string& path, const ReadOptions& options, ReadStats* stats) {
  const std::string ext = fileExtension(path);
  if (!isReadableImageExtension(ext))
    throw Error(path, ext.empty() ? "no file extension (expected .hdr, .exr, .png, .jpg)"
                                  : "unknown image extension '." + ext +
                                        "' (expected .hdr, .exr, .png, .jpg)");
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return readImageBytes(path, ext, bytes, options, stats);
}

void checkEncodedImageSize(const std::string& label, std::span<const unsigned char> bytes) {
  if (isPng(bytes))
    checkPngChunks(label, bytes);
  else if (!isJpeg(bytes))
    throw Error(label, "not a PNG or JPEG image (bad signature)");
  int w = 0, h = 0, n = 0;
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max()))
    throw Error(label, "image file too large to decode");
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n))
    throw Error(label, "cannot decode image (" + stbReason() + ")");
  checkImageSize(label, std::uint64_t(std::max(w, 0)), std::uint64_t(std::max(h, 0)));
}

Image readImageBytes(const std::string& path, const std::string& ext,
                     std::span<const unsigned char> bytes, const ReadOptions& options,
                     ReadStats* stats) {
  if (!isReadableImageExtension(ext))
    throw Error(path, "unknown image extension '." + ext + "' (expected .hdr, .exr, .png, .jpg)");
  if (bytes.empty()) throw Error(path, "empty file");
  Image img;
  bool ldr = false;
  if (ext == "hdr") {
    img = readRadianceHdr(path, bytes);
  } else if (ext == "exr") {
    img = readExr(path, bytes);
  } else {
    img = readStbLdr(path, bytes, options.ldrDecode, ext != "png");
    ldr = true;
  }
  if (img.width <= 0 || img.height <= 0) throw Error(path, "image has no pixels");
  ReadStats s = sanitize(img);
  s.ldr = ldr;
  if (stats) *stats = s;
  return img;
}

Srgb8Image readSrgb8Bytes(const std::string& label, std::span<const unsigned char> bytes) {
  if (bytes.empty()) throw Error(label, "empty file");
  const bool jpeg = checkStbInput(label, bytes, "PNG or JPEG image");
  MemoryReader reader{bytes.data(), bytes.size()};
  const bool sixteen =
      !jpeg && stbi_is_16_bit_from_memory(bytes.data(), static_cast<int>(bytes.size()));
  int w = 0, h = 0, n = 0;
  Srgb8Image img;
  if (sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> data(
        stbi_load_16_from_callbacks(&kCallbacks, &reader, &w, &h, &n, 3), stbi_image_free);
    if (!data) throw Error(label, "cannot decode image (" + stbReason() + ")");
    img.rgb.resize(std::size_t(w) * std::size_t(h) * 3);
    // 8-bit code c widens to 257 c: rounding v / 257 inverts it exactly.
    for (std::size_t i = 0; i < img.rgb.size(); ++i)
      img.rgb[i] = static_cast<std::uint8_t>((std::uint32_t(data.get()[i]) + 128) / 257);
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> data(
        stbi_load_from_callbacks(&kCallbacks, &reader, &w, &h, &n, 3), stbi_image_free);
    if (!data) throw Error(label, "cannot decode image (" + stbReason() + ")");
    img.rgb.assign(data.get(), data.get() + std::size_t(w) * std::size_t(h) * 3);
  }
  if (reader.readPastEnd) throw Error(label, "truncated image file");
  if (w <= 0 || h <= 0) throw Error(label, "image has no pixels");
  img.width = w;
  img.height = h;
  return img;
}

Srgb8Image readSrgb8Image(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == "png" || ext == "jpg" || ext == "jpeg")
    return readSrgb8Bytes(path, readFileBytes(path));
  // A linear image (or an unknown extension, which readImage names) encoded as an LDR texture.
  const Image linear = readImage(path);
  Srgb8Image img;
  img.width = linear.width;
  img.height = linear.height;
  img.rgb.resize(linear.size() * 3);
  for (std::size_t i = 0; i < linear.size(); ++i)
    for (int c = 0; c < 3; ++c)
      img.rgb[3 * i + c] =
          static_cast<std::uint8_t>(std::lround(linearToSrgb((&linear.pixels[i].x)[c]) * 255.0f));
  return img;
}

namespace {

void stbWriteToStream(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

std::string exrBytes(const std::string& path, const Image& img) {
  // tinyexr wants planar channels in B, G, R order (the order EXR readers expect on disk).
  const std::size_t n = img.size();
  std::vector<float> planes[3];
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(n);
    for (std::size_t i = 0; i < n; ++i) planes[c][i] = (&img.pixels[i].x)[2 - c];
  }
  float* ptrs[3] = {planes[0].data(), planes[1].data(), planes[2].data()};
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = 3;
  image.images = reinterpret_cast<unsigned char**>(ptrs);
  image.width = img.width;
  image.height = img.height;
  EXRChannelInfo channels[3];
  std::memset(channels, 0, sizeof(channels));
  const char* names[3] = {"B", "G", "R"};
  int pixelTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
  for (int c = 0; c < 3; ++c) std::strncpy(channels[c].name, names[c], 255);
  header.num_channels = 3;
  header.channels = channels;
  header.pixel_types = pixelTypes;
  header.requested_pixel_types = pixelTypes;
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0) {
    std::string why = err ? err : "unknown reason";
    if (err) FreeEXRErrorMessage(err);
    throw Error(path, "cannot encode OpenEXR (" + why + ")");
  }
  std::string out(reinterpret_cast<char*>(memory), size);
  std::free(memory);
  return out;
}

}  // namespace

std::string encodePng(const Srgb8Image& img, const std::string& name) {
  if (img.width < 1 || img.height < 1 ||
      img.rgb.size() != std::size_t(img.width) * std::size_t(img.height) * 3)
    throw Error(name, "cannot encode a PNG of " + std::to_string(img.width) + " x " +
                          std::to_string(img.height) + " pixels from " +
                          std::to_string(img.rgb.size()) + " codes");
  std::ostringstream os;
  if (!stbi_write_png_to_func(stbWriteToStream, &os, img.width, img.height, 3, img.rgb.data(),
                              img.width * 3))
    throw Error(name, "cannot encode PNG");
  return os.str();
}

void writeImage(const std::string& path, const Image& img, const WriteOptions& options) {
  const std::string ext = isStandardOutput(path) ? "png" : fileExtension(path);
  if (img.empty()) throw Error(path, "refusing to write an empty image");
  if (ext == "png") {
    std::vector<std::uint8_t> bytes(img.size() * 3);
    for (std::size_t i = 0; i < img.size(); ++i) {
      const Rgb t = toneMap(img.pixels[i], options.toneMap, options.exposureStops);
      for (int c = 0; c < 3; ++c)
        bytes[3 * i + c] = static_cast<std::uint8_t>(std::lround(linearToSrgb((&t.x)[c]) * 255.0f));
    }
    writeFileAtomically(path, [&](std::ostream& os) {
      if (!stbi_write_png_to_func(stbWriteToStream, &os, img.width, img.height, 3, bytes.data(),
                                  img.width * 3))
        throw Error(path, "cannot encode PNG");
    });
  } else if (ext == "hdr") {
    std::vector<float> data(img.size() * 3);
    for (std::size_t i = 0; i < img.size(); ++i)
      for (int c = 0; c < 3; ++c) data[3 * i + c] = (&img.pixels[i].x)[c];
    writeFileAtomically(path, [&](std::ostream& os) {
      if (!stbi_write_hdr_to_func(stbWriteToStream, &os, img.width, img.height, 3, data.data()))
        throw Error(path, "cannot encode Radiance HDR");
    });
  } else if (ext == "exr") {
    writeFileAtomically(path, exrBytes(path, img));
  } else {
    throw Error(path,
                "cannot write images with extension '." + ext + "' (expected .png, .exr or .hdr)");
  }
}

}  // namespace prt::image
