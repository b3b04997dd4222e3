// A run's outputs appear together or not at all: each is checked writable before any work,
// written under a temporary name beside it, and renamed into place once every one is written.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace rad {

/// Throws rad::Error naming `path` and what to do unless a file can be made there: its folder
/// exists and takes new files, and `path` is not a folder. Leaves nothing behind.
void check_writable(const std::string& path);

/// Files written under temporary names and renamed onto their own all at once by commit().
/// Not thread-safe.
class StagedFiles {
 public:
  StagedFiles() = default;
  /// Removes every temporary file not committed: a run that fails leaves no output of it.
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  /// Calls `write` with a temporary name beside `path` that keeps its extension (writers choose
  /// the format by it). A rad::Error it throws is thrown again naming `path`.
  void write(const std::string& path, const std::function<void(const std::string&)>& write);
  /// Renames every file written onto its path, in the order written. Throws rad::Error.
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> files_;  // temporary, final
};

}  // namespace rad
