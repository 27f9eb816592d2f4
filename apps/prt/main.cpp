// prt: the prtkit command line. `prt VERB --help` for each verb.

#include <csignal>
#include <cstdio>
#include <iostream>
#include <mutex>

#include <unistd.h>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"

#ifndef PRT_VERSION
#define PRT_VERSION "dev"
#endif

namespace prt::cli {

Globals& globals() {
  static Globals g;
  return g;
}

void info(const std::string& line) {
  if (!globals().quiet) std::cerr << line << '\n';
}

void warn(const std::string& line) {
  std::cerr << "prt: warning: " << line << '\n';
}

ProgressFn progressBar(const std::string& label) {
  const bool show = !globals().quiet && ::isatty(STDERR_FILENO);
  return [show, label, last = -1](double f) mutable {
    if (cancelRequested()) return false;
    if (!show) return true;
    const int pct = static_cast<int>(f * 100.0);
    if (pct == last) return true;
    last = pct;
    const int width = 30, filled = pct * width / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%%s", label.c_str(), filled,
                 "##############################", width - filled, "", pct, pct >= 100 ? "\n" : "");
    std::fflush(stderr);
    return true;
  };
}

}  // namespace prt::cli

namespace {

extern "C" void onSigint(int) {
  if (prt::cancelRequested()) std::_Exit(130);  // second Ctrl-C: leave at once
  prt::requestCancel();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace prt::cli;
  CLI::App app{"prtkit: precomputed radiance transfer — bake, relight, render, validate", "prt"};
  app.require_subcommand(1);
  app.fallthrough();  // -j, -q, -v also after the verb: prt bake ... -q
  app.set_version_flag("--version", std::string("prt ") + PRT_VERSION);
  auto& g = globals();
  app.add_option("-j,--threads", g.threads, "Worker threads (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", g.quiet, "No progress or chatter on stderr");
  app.add_flag("-v,--verbose", g.verbose, "More detail on stderr");

  addLightCommand(app);
  addBakeCommand(app);
  addExportCommand(app);
  addInfoCommand(app);
  addRenderCommand(app);
  addValidateCommand(app);
  addReferenceCommand(app);
  addViewCommand(app);
  addMergeCommand(app);
  addDemoCommand(app);
  addWebCommand(app);

  std::signal(SIGINT, onSigint);
  std::unique_ptr<prt::ThreadLimit> limit;
  app.parse_complete_callback([&] { limit = std::make_unique<prt::ThreadLimit>(g.threads); });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line, like every other error: "prt VERB: error: what (see prt VERB --help)".
    std::string verb = "prt";
    for (auto* sub : app.get_subcommands()) verb += " " + sub->get_name();
    if (app.get_subcommands().empty()) {
      // "prt frob": name the unknown verb and the known ones, not "a subcommand is required".
      for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-j" || a == "--threads") {
          ++i;
          continue;
        }
        if (a.empty() || a[0] == '-') continue;
        std::string verbs;
        for (const CLI::App* sub : app.get_subcommands({}))
          verbs += (verbs.empty() ? "" : ", ") + sub->get_name();
        std::cerr << "prt: error: unknown verb '" << a << "' (one of: " << verbs << ")\n";
        return e.get_exit_code();
      }
    }
    std::cerr << verb << ": error: " << e.what() << " (see " << verb << " --help)\n";
    return e.get_exit_code();
  } catch (const prt::Cancelled&) {
    std::cerr << "\nprt: cancelled\n";
    return 130;
  } catch (const std::exception& e) {
    std::string verb = "prt";
    for (auto* sub : app.get_subcommands()) verb += " " + sub->get_name();
    std::cerr << verb << ": error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
