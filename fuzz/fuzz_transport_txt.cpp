// The GAMES202 transport.txt through prt::parseGames202Transport.
#include <string>

#include "fuzz_common.hpp"
#include "prt/io/games202_transport.hpp"

PRT_FUZZ_TARGET(prt::parseGames202Transport(std::string(prt::fuzz::text(data, size)), "fuzz.txt"))
