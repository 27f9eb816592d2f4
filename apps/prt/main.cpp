// prt: the prtkit command line. `prt VERB --help` for each verb.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include <unistd.h>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/version.hpp"
#include "stderr_line.hpp"

namespace prt::cli {

Globals& globals() {
  static Globals g;
  return g;
}

void info(const std::string& line) {
  if (!globals().quiet) printLine(line);
}

void warn(const std::string& line) {
  if (globals().silent) return;
  printLine("prt: warning: " + oneLine(line));
}

namespace {

/// "48 s", "5 min 12 s", "1 h 03 min".
std::string durationText(double s) {
  const long long t = std::llround(std::max(0.0, s));
  char buf[32];
  if (t < 60)
    std::snprintf(buf, sizeof buf, "%lld s", t);
  else if (t < 3600)
    std::snprintf(buf, sizeof buf, "%lld min %02lld s", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld h %02lld min", t / 3600, (t % 3600) / 60);
  return buf;
}

/// The time left if the rest goes as fast as the part done: t (1 − f) / f; "ETA ?" before
/// anything is done.
std::string etaText(double f, double t) {
  if (!(f > 0.0) || t < 0.5) return "ETA ?";
  return "ETA " + durationText(t * (1.0 - std::min(f, 1.0)) / f);
}

}  // namespace

ProgressFn progressBar(const std::string& label) {
  if (globals().quiet) return [](double) { return !cancelRequested(); };
  if (::isatty(STDERR_FILENO)) {
    using Clock = std::chrono::steady_clock;
    return [label, last = -1, start = Clock::now()](double f) mutable {
      if (cancelRequested()) return false;
      const int pct = static_cast<int>(f * 100.0);
      if (pct == last) return true;
      last = pct;
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      const int width = 30, filled = pct * width / 100;
      std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %-16s%s", label.c_str(), filled,
                   "##############################", width - filled, "", pct,
                   pct >= 100 ? durationText(t).c_str() : etaText(f, t).c_str(),
                   pct >= 100 ? "\n" : "");
      std::fflush(stderr);
      return true;
    };
  }
  // Not a terminal (a pipe, a log file, CI): a plain line at most every few seconds, so long
  // work is never silent — "reference: 35% (12 s, ETA 22 s)". PRT_PROGRESS_INTERVAL (seconds, default 5)
  // sets the spacing; the tests set it to 0.
  double interval = 5.0;
  if (const char* env = std::getenv("PRT_PROGRESS_INTERVAL")) {
    char* end = nullptr;
    const double v = std::strtod(env, &end);
    if (end != env && *end == '\0' && std::isfinite(v) && v >= 0) interval = v;
  }
  using Clock = std::chrono::steady_clock;
  return [label, interval, start = Clock::now(), next = interval, lastPct = -1](double f) mutable {
    if (cancelRequested()) return false;
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    const int pct = static_cast<int>(f * 100.0);
    if (t >= next && pct != lastPct && pct < 100) {
      std::fprintf(stderr, "%s: %d%% (%s, %s)\n", label.c_str(), pct, durationText(t).c_str(),
                   etaText(f, t).c_str());
      std::fflush(stderr);
      lastPct = pct;
      next = t + interval;
    }
    return true;
  };
}

}  // namespace prt::cli

namespace {

extern "C" void onSigint(int) {
  if (prt::cancelRequested()) {
    // Second Ctrl-C: leave at once (write(2) and _Exit are async-signal-safe; a writer's
    // temporary left behind is removed by the next run that writes there).
    static const char kText[] = "\nprt: cancelled at once\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kText, sizeof kText - 1);
    std::_Exit(130);
  }
  prt::requestCancel();
}

/// "prt bake", or "prt" before a verb was parsed.
std::string verbName(const CLI::App& app) {
  std::string verb = "prt";
  for (const auto* sub : app.get_subcommands()) verb += " " + sub->get_name();
  return verb;
}

/// What a verb was doing, for messages that cannot say more ("out of memory while ...").
const char* activity(const std::string& verb) {
  if (verb == "prt light") return "loading or projecting the environment";
  if (verb == "prt bake") return "loading or baking the scene";
  if (verb == "prt export") return "reading or converting the bake";
  if (verb == "prt info") return "reading the file";
  if (verb == "prt render") return "rendering";
  if (verb == "prt validate") return "validating";
  if (verb == "prt reference") return "computing the reference";
  if (verb == "prt view") return "viewing";
  if (verb == "prt merge") return "merging the bakes";
  if (verb == "prt compress") return "compressing the transfer";
  if (verb == "prt denoise") return "denoising the lightmap";
  if (verb == "prt demo") return "running the demo";
  if (verb == "prt web") return "writing the browser viewer";
  if (verb == "prt unwrap") return "unwrapping the mesh";
  if (verb == "prt completions" || verb == "prt manpage") return "writing the text";
  return "reading the command line";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace prt::cli;
  CLI::App app{"prtkit: precomputed radiance transfer — bake, relight, render, validate", "prt"};
  app.require_subcommand(1);
  app.fallthrough();  // -j, -q, -v also after the verb: prt bake ... -q
  app.set_version_flag("--version", std::string("prt ") + prt::kVersion);
  auto& g = globals();
  app.add_option("-j,--threads", g.threads, "Worker threads (0 = all cores)")
      ->check(intRange(0, 4096));
  app.add_flag("-q,--quiet", g.quiet, "No progress or chatter on stderr");
  app.add_flag("-v,--verbose", g.verbose, "More detail on stderr");

  addLightCommand(app);
  addBakeCommand(app);
  addProbesCommand(app);
  addExportCommand(app);
  addInfoCommand(app);
  addRenderCommand(app);
  addValidateCommand(app);
  addReferenceCommand(app);
  addViewCommand(app);
  addMergeCommand(app);
  addCompressCommand(app);
  addDenoiseCommand(app);
  addDemoCommand(app);
  addWebCommand(app);
  addUnwrapCommand(app);
  addCompletionsCommands(app);
  oneValuePerOption(app);

  std::signal(SIGINT, onSigint);
  // What the writers did besides writing (a stale temporary of a killed run removed): always
  // said, as it touched the disk.
  prt::setFileNoteHandler(
      [](const std::string& line) { printLine("prt: note: " + oneLine(line)); });
  std::unique_ptr<prt::ThreadLimit> limit;
  app.parse_complete_callback([&] { limit = std::make_unique<prt::ThreadLimit>(g.threads); });

  try {
    // The PRT_MAX_* variables are read once, here: a bad one is refused at once, whatever the
    // verb and whether or not it would have consulted the limit.
    prt::limits();
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line, like every other error: "prt VERB: error: what (see prt VERB --help)".
    const std::string verb = verbName(app);
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
        printLine("prt: error: unknown verb '" + oneLine(a, 60) + "' (one of: " + verbs + ")");
        return e.get_exit_code();
      }
    }
    printLine(verb + ": error: " + oneLine(e.what()) + " (see " + verb + " --help)");
    return e.get_exit_code();
  } catch (const QuietFailure&) {
    return 1;
  } catch (const prt::Cancelled&) {
    printLine("\nprt: cancelled");
    return 130;
  } catch (const std::bad_alloc&) {
    // No allocation may be left to build a message with: fixed text only.
    const std::string verb = verbName(app);
    std::fprintf(stderr,
                 "%s: error: out of memory while %s (the input is too large for this "
                 "machine's memory)\n",
                 verb.c_str(), activity(verb));
    return 1;
  } catch (const prt::Error& e) {
    printLine(verbName(app) + ": error: " + oneLine(e.what()));
    return 1;
  } catch (const std::exception& e) {
    // Not one of our messages (std::stoull's "stoull", a filesystem_error, ...): say what kind
    // of failure it was rather than echo a bare function name.
    const std::string verb = verbName(app);
    const char* kind = dynamic_cast<const std::out_of_range*>(&e)       ? "a number is out of range"
                       : dynamic_cast<const std::invalid_argument*>(&e) ? "a value is malformed"
                       : dynamic_cast<const std::length_error*>(&e)     ? "a size is too large"
                                                                        : "unexpected failure";
    printLine(verb + ": error: " + kind + " while " + activity(verb) + " (" +
              oneLine(e.what(), 200) + ")");
    return 1;
  }
  return 0;
}
