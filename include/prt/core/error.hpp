#pragma once
// Errors. The library never prints and never exits: it throws prt::Error, whose what() is one
// line meant for a user ("bunny.obj: face 12 references vertex 900 (mesh has 512)"). The CLI
// prefixes "prt VERB: error: " and exits non-zero. PRT_CHECK guards internal invariants.

#include <stdexcept>
#include <string>

namespace prt {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  /// An error about a file: "FILE: message".
  Error(const std::string& file, const std::string& message)
      : std::runtime_error(file.empty() ? message : file + ": " + message) {}
};

/// Thrown when a long operation is cancelled through its progress callback (or Ctrl-C).
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

[[noreturn]] void checkFailed(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace prt

#define PRT_CHECK(cond, msg)                                           \
  do {                                                                 \
    if (!(cond)) ::prt::checkFailed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
