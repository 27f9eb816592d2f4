#pragma once
// Writing outputs safely: everything goes to a temporary file beside the destination and is
// renamed into place only when complete, so a failure never leaves a half-written result.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace prt {

/// Calls write(stream) on a temporary file beside `path`, then renames it to `path`.
/// On any exception the temporary is removed and the exception rethrown.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);
/// Same for a byte buffer.
void writeFileAtomically(const std::string& path, std::string_view bytes);
/// Reads a whole regular file (never a pipe, device or socket: a FIFO would block in open());
/// throws Error("path: cannot open ...") on failure, or when it is larger than
/// limits().maxFileBytes (PRT_MAX_FILE_BYTES).
std::vector<unsigned char> readFileBytes(const std::string& path);
/// The same with a cap of the caller's (a format's own limit), named `capName` in the refusal.
std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t maxBytes,
                                         const char* capName);
/// Throws Error naming `path` if its directory does not exist or is not writable.
void checkWritable(const std::string& path);
/// Lower-case extension without the dot ("hdr", "exr", "gz"); "" if none.
std::string fileExtension(const std::string& path);

}  // namespace prt
