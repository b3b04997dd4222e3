// Files that appear complete or not at all.
#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(AtomicFile, TheOldFileStaysUntilCommitAndNoTemporaryRemains) {
  const fs::path dir = fs::temp_directory_path() / ("rad_atomic_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path target = dir / "out.bin";
  std::ofstream(target) << "old";
  for (const bool durable : {false, true}) {
    {
      AtomicFile f(target.string());
      if (durable) f.make_durable();
      f.stream() << "new" << durable;
      EXPECT_EQ(read(target), durable ? "new0" : "old") << "replaced before commit";
      f.commit();
    }
    EXPECT_EQ(read(target), durable ? "new1" : "new0");
  }
  {
    AtomicFile abandoned(target.string());
    abandoned.stream() << "half";
  }  // destroyed without commit: as if the write failed
  EXPECT_EQ(read(target), "new1");
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u) << "a temporary file was left behind";
  EXPECT_THROW(AtomicFile((dir / "no/such/folder/x").string()), Error);
  fs::remove_all(dir);
}

TEST(AtomicFile, StaleTemporariesOfDeadRunsAreRemovedAndLiveOnesKept) {
  const fs::path dir = fs::temp_directory_path() / ("rad_stale_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path target = dir / "run.ckpt";
  // A pid beyond any the kernel hands out (pid_max is at most 2^22): its writer is gone.
  const fs::path dead = dir / "run.ckpt.tmp-99999999";
  const fs::path live = dir / ("run.ckpt.tmp-" + std::to_string(getpid()));
  const fs::path other = dir / "other.ckpt.tmp-99999999";
  for (const fs::path& p : {dead, live, other}) std::ofstream(p) << "x";
  remove_stale_temporaries(target.string());
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
