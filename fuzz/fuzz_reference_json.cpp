// A reference file (prt reference's JSON) through prt::io::parseReferenceJson.
#include "fuzz_common.hpp"
#include "prt/io/reference_file.hpp"

PRT_FUZZ_TARGET(prt::io::parseReferenceJson(prt::fuzz::text(data, size), "fuzz.json"))
