// prt light: placeholder until the verb is implemented.
#include "cli.hpp"

namespace prt::cli {
void addLightCommand(CLI::App& root) { (void)root; }
}  // namespace prt::cli
