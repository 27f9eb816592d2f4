#pragma once
// How the front ends name their options in messages, worded once: the command line says
// "--bands 20: must be 1..16", Python "bands=20: must be 1..16". A library check that refuses an
// option's value (transport/bake_request.hpp) takes the spelling and names the option as the
// user wrote it.

#include <string>

namespace prt {

/// How a front end spells its options: "--seam-fix" (the command line) or "seam_fix=" (Python
/// keywords).
enum class OptionSpelling { Cli, Python };

/// `name` ("bands", "seam-fix") as the front end spells it: "--bands" or "bands=" ("seam_fix=").
std::string optionName(OptionSpelling spelling, const std::string& name);
/// The option named without a value: "--albedo" or "albedo".
std::string optionLabel(OptionSpelling spelling, const std::string& name);
/// Throws prt::Error("--bands 20: must be 1..16" / "bands=20: must be 1..16") unless
/// lo <= value <= hi.
void checkOptionRange(OptionSpelling spelling, const std::string& name, long long value,
                      long long lo, long long hi);

}  // namespace prt
