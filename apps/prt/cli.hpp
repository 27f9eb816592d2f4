#pragma once
// Shared pieces of the prt command line. Each verb lives in its own file (light.cpp, bake.cpp,
// ...) and exposes one function `void addXxxCommand(CLI::App& root)` that registers a
// subcommand whose callback does the work; errors are thrown as prt::Error and printed by main
// as "prt VERB: error: MESSAGE".

#include <CLI/CLI.hpp>
#include <exception>
#include <string>

#include "prt/core/progress.hpp"

namespace prt::cli {

/// Global options, parsed before any verb runs.
struct Globals {
  int threads = 0;       ///< -j/--threads, 0 = all cores
  bool quiet = false;    ///< -q
  bool verbose = false;  ///< -v
  bool silent = false;   ///< no warnings either (the MPI ranks other than rank 0)
};
Globals& globals();

/// A failure another process reports (rank 0 of an MPI job, for every rank): main exits with
/// status 1 and prints nothing.
struct QuietFailure : std::exception {
  const char* what() const noexcept override { return "failure reported elsewhere"; }
};

/// A progress callback drawing "label [#####     ] 42%" on stderr when stderr is a terminal
/// (and not quiet); returns false (cancel) after Ctrl-C.
ProgressFn progressBar(const std::string& label);
/// Prints a line of chatter on stderr unless quiet.
void info(const std::string& line);
/// Prints "prt: warning: ..." on stderr (even when quiet).
void warn(const std::string& line);

// The verbs.
void addLightCommand(CLI::App& root);
void addBakeCommand(CLI::App& root);
void addProbesCommand(CLI::App& root);
void addExportCommand(CLI::App& root);
void addInfoCommand(CLI::App& root);
void addRenderCommand(CLI::App& root);
void addValidateCommand(CLI::App& root);
void addReferenceCommand(CLI::App& root);
void addViewCommand(CLI::App& root);
void addMergeCommand(CLI::App& root);
void addCompressCommand(CLI::App& root);
void addDenoiseCommand(CLI::App& root);
void addDemoCommand(CLI::App& root);
void addWebCommand(CLI::App& root);
void addUnwrapCommand(CLI::App& root);
/// `prt completions bash|zsh` and `prt manpage`, generated from `root` (add them last).
void addCompletionsCommands(CLI::App& root);

}  // namespace prt::cli
