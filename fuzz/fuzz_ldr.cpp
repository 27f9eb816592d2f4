// PNG and JPEG through prt::image::readImageBytes (stb_image behind our wrapper); the format
// follows the signature, so one corpus covers both.
#include "fuzz_common.hpp"
#include "prt/image/image_io.hpp"

PRT_FUZZ_TARGET({
  const bool jpeg = size >= 2 && data[0] == 0xFF && data[1] == 0xD8;
  prt::image::readImageBytes(jpeg ? "fuzz.jpg" : "fuzz.png", jpeg ? "jpg" : "png",
                             prt::fuzz::bytes(data, size));
})
