// Radiance .hdr through prt::image::readImageBytes.
#include "fuzz_common.hpp"
#include "prt/image/image_io.hpp"

PRT_FUZZ_TARGET(prt::image::readImageBytes("fuzz.hdr", "hdr", prt::fuzz::bytes(data, size)))
