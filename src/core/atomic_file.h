// Output files that appear complete or not at all: written under a temporary name in the same
// folder, renamed over the final name only when complete.
// A process killed at any point leaves the old file or the new one, never a torn one.
#pragma once

#include <fstream>
#include <string>

namespace rad {

class AtomicFile {
 public:
  /// Opens "<path>.tmp-<pid>" for binary writing; throws rad::Error if it cannot.
  explicit AtomicFile(std::string path);
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  /// Makes commit() fsync the data before the rename and the folder after it, so a power cut
  /// leaves the old file or the new one (checkpoints need it; outputs can be rewritten).
  void make_durable() { durable_ = true; }
  /// Flushes, closes and renames onto the final path; throws rad::Error on any failure.
  void commit();

 private:
  std::string path_, temp_;
  std::ofstream out_;
  bool committed_ = false;
  bool durable_ = false;
};

/// Removes "<path>.tmp-<pid>" files that no running process owns: what a run killed while
/// writing `path` (kill -9) left behind.
void remove_stale_temporaries(const std::string& path);

}  // namespace rad
