#include "scene/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace rad {

std::string read_text_file(const std::string& path, const SourceLoc& requested_at) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    throw Error(requested_at, "cannot open '" + path + "': no such file");
  }
  if (!fs::is_regular_file(status)) {
    throw Error(requested_at, "cannot read '" + path + "': not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error(requested_at, "cannot open '" + path + "': " + std::strerror(errno));
  }
  // Read straight into the string at the size the file has (a stream copy of a model of tens of
  // MiB cost a tenth of its import), then whatever it grew by meanwhile.
  std::string text;
  const uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > 0) {
    text.resize(size_t(size));
    in.read(text.data(), std::streamsize(size));
    text.resize(size_t(in.gcount()));
  }
  char rest[4096];
  while (in.read(rest, sizeof rest) || in.gcount() > 0) text.append(rest, size_t(in.gcount()));
  if (in.bad()) {
    throw Error(requested_at, "cannot read '" + path + "': " + std::strerror(errno));
  }
  return text;
}

}  // namespace rad
