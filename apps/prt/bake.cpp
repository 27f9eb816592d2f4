// prt bake: placeholder until the verb is implemented.
#include "cli.hpp"

namespace prt::cli {
void addBakeCommand(CLI::App& root) { (void)root; }
}  // namespace prt::cli
