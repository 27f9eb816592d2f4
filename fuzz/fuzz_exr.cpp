// OpenEXR through prt::image::readImageBytes (the OpenEXR library behind our memory stream).
#include "fuzz_common.hpp"
#include "prt/image/image_io.hpp"

PRT_FUZZ_TARGET(prt::image::readImageBytes("fuzz.exr", "exr", prt::fuzz::bytes(data, size)))
