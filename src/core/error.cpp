#include "core/error.h"

#include <fmt/format.h>

#include <atomic>
#include <cstdio>

namespace rad {

std::string to_string(const SourceLoc& loc) {
  if (loc.line <= 0) return loc.file;
  if (loc.column <= 0) return fmt::format("{}:{}", loc.file, loc.line);
  return fmt::format("{}:{}:{}", loc.file, loc.line, loc.column);
}

namespace {
std::string compose(const SourceLoc& loc, const char* kind, const std::string& message) {
  std::string where = to_string(loc);
  return where.empty() ? std::string(kind) + ": " + message : where + ": " + kind + ": " + message;
}
}  // namespace

Error::Error(SourceLoc loc, const std::string& message)
    : std::runtime_error(compose(loc, "error", message)), loc_(std::move(loc)), message_(message) {}

Error::Error(const std::string& message)
    : std::runtime_error("error: " + message), message_(message) {}

namespace {
std::atomic<bool> warnings_shown{true};
}  // namespace

void warn(const SourceLoc& loc, const std::string& message) {
  if (!warnings_shown.load(std::memory_order_relaxed)) return;
  std::fprintf(stderr, "%s\n", compose(loc, "warning", message).c_str());
}

void show_warnings(bool on) { warnings_shown.store(on, std::memory_order_relaxed); }

}  // namespace rad
