#include "core/file_extension.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace rad {

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

}  // namespace rad
