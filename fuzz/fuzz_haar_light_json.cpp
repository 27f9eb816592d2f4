// Haar light files (prt light --basis haar) through prt::io::parseHaarLightJson.
#include "fuzz_common.hpp"
#include "prt/io/haar_light_file.hpp"

PRT_FUZZ_TARGET(prt::io::parseHaarLightJson(prt::fuzz::text(data, size), "fuzz.json"))
