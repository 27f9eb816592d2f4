// prt info: placeholder until the verb is implemented.
#include "cli.hpp"

namespace prt::cli {
void addInfoCommand(CLI::App& root) { (void)root; }
}  // namespace prt::cli
