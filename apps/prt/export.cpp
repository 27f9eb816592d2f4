// prt export: placeholder until the verb is implemented.
#include "cli.hpp"

namespace prt::cli {
void addExportCommand(CLI::App& root) { (void)root; }
}  // namespace prt::cli
