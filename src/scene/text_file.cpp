#include "scene/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

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
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) {
    throw Error(requested_at, "cannot read '" + path + "': " + std::strerror(errno));
  }
  return bytes.str();
}

}  // namespace rad
