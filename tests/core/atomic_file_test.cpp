// Files that appear complete or not at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
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

}  // namespace
}  // namespace rad
