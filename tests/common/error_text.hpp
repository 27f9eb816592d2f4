#pragma once
// The one line a prt::Error says, for tests that check a refusal names what it should.

#include <functional>
#include <string>

#include "prt/core/error.hpp"

namespace prt::testing {

/// What f() threw as prt::Error ("" when it threw nothing).
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace prt::testing
