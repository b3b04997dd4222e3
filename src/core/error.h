// User-facing errors that carry the source location of the offending input.
#pragma once

#include <stdexcept>
#include <string>

namespace rad {

/// A position in an input file; line and column count from 1 (0 = unknown).
struct SourceLoc {
  std::string file;
  int line = 0;
  int column = 0;
};

/// Formats "file:line:column" (omitting unknown parts).
std::string to_string(const SourceLoc& loc);

/// An error caused by the user's input. what() is the whole one-line message,
/// "file:line:column: error: message", ready to print.
class Error : public std::runtime_error {
 public:
  Error(SourceLoc loc, const std::string& message);
  explicit Error(const std::string& message);  // no location (e.g. a bad option)

  const SourceLoc& loc() const { return loc_; }
  const std::string& message() const { return message_; }

 private:
  SourceLoc loc_;
  std::string message_;
};

/// A warning printed once on stderr in the same format ("...: warning: ..."), unless warnings
/// are off. Every warning goes through here, so --quiet (errors only) silences them all.
void warn(const SourceLoc& loc, const std::string& message);

/// Turns warn() on or off for the whole process (main does it once, for --quiet). Thread-safe.
void show_warnings(bool on);

}  // namespace rad
