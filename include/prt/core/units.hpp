#pragma once
// Quantities written for people.

#include <cstddef>
#include <string>

namespace prt {

/// "2.5 KB", "26 GB": decimal units, three significant digits.
std::string bytesText(std::size_t bytes);

}  // namespace prt
