#pragma once
// JSON is written one way: a value built with nlohmann::json (escaping, number formatting and
// non-finite numbers as null are the library's), laid out by formatJson: light files, validation
// and reference reports, prt-data.js. The bake file's glTF JSON chunk is nlohmann's compact dump
// too (src/io/bake_file.cpp), unordered as glTF tools expect nothing else.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace prt {

/// Keys keep the order they were set in, so a file reads in the order its writer meant.
using Json = nlohmann::ordered_json;

/// A float as the JSON number with the fewest digits that reads back as exactly that float
/// (0.1f is written 0.1, not 0.100000001490116). Non-finite values become null.
Json jsonFloat(float v);
/// An array of floats, each by jsonFloat.
Json jsonFloats(const float* v, std::size_t n);

/// Pretty-printed with `indent` spaces, but an array that holds only numbers (an RGB triple, a
/// row of coefficients, a list of vertices) stays on one line. A trailing newline.
/// indent 0: the compact form, no newline.
std::string formatJson(const Json& value, int indent = 2);

/// JSON read one way: the nesting checked before the recursive parser sees it (core/limits.hpp),
/// then parsed; a syntax error or a number beyond double range is one prt::Error naming `name`
/// ("invalid JSON at byte N").
nlohmann::json parseJsonText(std::string_view text, const std::string& name);

}  // namespace prt
