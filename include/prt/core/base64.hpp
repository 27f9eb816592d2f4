#pragma once
// Base64 (RFC 4648, the standard alphabet, '=' padding): how JSON and data URIs carry bytes
// (a glTF's embedded images, a probe grid's texture atlas).

#include <string>
#include <string_view>

namespace prt {

std::string base64(std::string_view bytes);

}  // namespace prt
