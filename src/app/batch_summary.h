// OUTDIR/batch.json: one row per scene of a batch, merged by every shard that finishes.
#pragma once

#include <cstdint>
#include <string>

namespace rad {

/// One scene's outcome, as the summary keeps it.
struct BatchRecord {
  std::string name;    // the scene's output name in OUTDIR
  std::string scene;   // its path as listed
  std::string status;  // "ok", "partial" or "failed"
  std::string detail;  // why it stopped, or the error
  double seconds = 0.0;
  int64_t shots = 0;
  uint64_t vertices = 0;
  int shard = 0, shards = 1;
};

/// Puts `r` into OUTDIR/batch.json (schema "rad-batch", version 1) under an exclusive lock on
/// OUTDIR/batch.lock, rewriting the file atomically: shards that finish in any order, on any
/// number of machines sharing the folder, each add their rows and never lose another's. A
/// summary that does not parse is replaced, with a warning. Throws rad::Error on I/O failure.
void merge_batch_record(const std::string& dir, const BatchRecord& r);

}  // namespace rad
