#include "core/memory.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string_view>

#include "core/error.h"

namespace rad {

size_t resident_bytes() {
  std::ifstream in("/proc/self/statm");
  size_t total = 0, resident = 0;
  if (!(in >> total >> resident)) return 0;
  return resident * size_t(sysconf(_SC_PAGESIZE));
}

size_t machine_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  size_t bytes = pages > 0 && page > 0 ? size_t(pages) * size_t(page) : 0;
  // cgroup v2 ("max" when unlimited), then v1.
  for (const char* path :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    unsigned long long limit = 0;
    if (in >> limit && limit > 0 && (bytes == 0 || limit < bytes)) bytes = size_t(limit);
  }
  return bytes;
}

size_t parse_byte_size(const std::string& text) {
  double value = 0.0;
  int used = 0;
  const auto fail = [&]() -> size_t {
    throw Error("'" + text + "' is not a size (examples: 512M, 8G, 1.5GiB, 2000000000)");
  };
  if (std::sscanf(text.c_str(), "%lf%n", &value, &used) != 1 || !(value > 0.0) ||
      !std::isfinite(value)) {
    return fail();
  }
  std::string unit(text.substr(size_t(used)));
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  double scale = 1.0;
  const std::string_view u(unit);
  const std::string_view prefixes = "KMGT";
  if (!u.empty() && u != "B") {
    const size_t k = prefixes.find(u[0]);
    if (k == std::string_view::npos ||
        (u.size() > 1 && u.substr(1) != "B" && u.substr(1) != "IB")) {
      return fail();
    }
    scale = std::pow(1024.0, double(k + 1));
  }
  const double bytes = value * scale;
  if (bytes > 1e18) return fail();
  return size_t(bytes);
}

std::string format_bytes(double bytes) {
  if (bytes >= 1024.0 * 1024 * 1024)
    return fmt::format("{:.1f} GiB", bytes / (1024.0 * 1024 * 1024));
  if (bytes >= 1024.0 * 1024) return fmt::format("{:.0f} MiB", bytes / (1024.0 * 1024));
  return fmt::format("{:.0f} KiB", bytes / 1024.0);
}

}  // namespace rad
