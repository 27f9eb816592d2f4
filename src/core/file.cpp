#include "prt/core/file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt {

namespace fs = std::filesystem;

void checkWritable(const std::string& path) {
  if (path.empty()) throw Error("output path is empty");
  fs::path p(path);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error(path, "directory " + dir.string() + " does not exist");
  if (fs::is_directory(p, ec)) throw Error(path, "is a directory");
  if (::access(dir.c_str(), W_OK) != 0) throw Error(path, "directory is not writable");
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  checkWritable(path);
  std::random_device rd;
  const std::string tmp = path + ".tmp" + std::to_string(rd() % 1000000);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error(path, "cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw Error(path, "write failed (disk full?)");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw Error(path, "cannot rename temporary file: " + ec.message());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

std::vector<unsigned char> readFileBytes(const std::string& path) {
  return readFileBytes(path, limits().maxFileBytes, "PRT_MAX_FILE_BYTES");
}

std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t maxBytes,
                                         const char* capName) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st)) throw Error(path, "is a directory, expected a file");
  // A FIFO with no writer would block in open() forever, and a pipe or device has no size to
  // check against the cap: only regular files are read.
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw Error(path, "is not a regular file (a pipe, device or socket); give a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open (does it exist and is it readable?)");
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw Error(path, "cannot read");
  checkLimit(path, "file size", static_cast<std::uint64_t>(size), maxBytes, capName);
  in.seekg(0, std::ios::beg);
  std::vector<unsigned char> data(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(data.data()), size))
    throw Error(path, "read failed");
  return data;
}

std::string fileExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace prt
