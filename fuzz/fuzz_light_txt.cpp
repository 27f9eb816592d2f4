// The GAMES202 light.txt through prt::io::parseLightGames202.
#include "fuzz_common.hpp"
#include "prt/io/light_file.hpp"

PRT_FUZZ_TARGET(prt::io::parseLightGames202(prt::fuzz::text(data, size), "fuzz.txt"))
