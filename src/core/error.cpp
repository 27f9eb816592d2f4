#include "prt/core/error.hpp"

namespace prt {

void checkFailed(const char* expr, const char* file, int line, const std::string& msg) {
  throw Error(std::string("internal error: ") + msg + " (" + expr + " at " + file + ":" +
              std::to_string(line) + ")");
}

}  // namespace prt
