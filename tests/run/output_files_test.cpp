// A run's outputs: refused before any work when they cannot be written, and renamed into place
// together or not at all.
#include "run/output_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

struct OutputFilesTest : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("rad_output_files_" + std::to_string(getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  size_t files_in_dir() const {
    size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
  }
};

std::string read(const fs::path& p) {
  std::ifstream f(p);
  return {std::istreambuf_iterator<char>(f), {}};
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST_F(OutputFilesTest, CheckWritableNamesThePathAndWhatToDo) {
  EXPECT_NO_THROW(check_writable((dir / "a.ply").string()));
  EXPECT_EQ(files_in_dir(), 0u) << "the probe is removed";
  try {
    check_writable((dir / "nodir" / "a.ply").string());
    FAIL() << "a missing folder";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().file, (dir / "nodir" / "a.ply").string());
    EXPECT_NE(e.message().find("does not exist; create it"), std::string::npos) << e.what();
  }
  try {
    check_writable(dir.string());
    FAIL() << "a folder";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("is a folder"), std::string::npos) << e.what();
  }
  write_text((dir / "file").string(), "x");
  EXPECT_THROW(check_writable((dir / "file" / "a.ply").string()), Error) << "not a folder";
  if (geteuid() != 0) {  // root writes anywhere
    fs::create_directories(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(check_writable((dir / "locked" / "a.ply").string()), Error);
    fs::permissions(dir / "locked", fs::perms::owner_all);
  }
}

TEST_F(OutputFilesTest, CommitRenamesEveryFileAndTheTemporariesKeepTheExtension) {
  const std::string a = (dir / "a.ply").string(), b = (dir / "b.png").string();
  write_text(a, "old");
  StagedFiles files;
  files.write(a, [&](const std::string& path) {
    EXPECT_EQ(fs::path(path).extension(), ".ply");
    EXPECT_NE(path, a);
    write_text(path, "new a");
  });
  files.write(b, [&](const std::string& path) {
    EXPECT_EQ(fs::path(path).extension(), ".png");
    write_text(path, "new b");
  });
  EXPECT_EQ(read(a), "old") << "nothing in place before commit";
  EXPECT_FALSE(fs::exists(b));
  files.commit();
  EXPECT_EQ(read(a), "new a");
  EXPECT_EQ(read(b), "new b");
  EXPECT_EQ(files_in_dir(), 2u) << "no temporaries left";
}

TEST_F(OutputFilesTest, AFailedWriteLeavesNoneOfTheOutputsAndNamesTheFinalPath) {
  const std::string a = (dir / "a.ply").string(), b = (dir / "b.png").string();
  write_text(b, "old b");
  try {
    StagedFiles files;
    files.write(a, [&](const std::string& path) { write_text(path, "new a"); });
    files.write(b, [&](const std::string& path) {
      write_text(path, "half");
      throw Error(SourceLoc{path, 0, 0}, "PNG encoding failed");
    });
    files.commit();
    FAIL() << "the second write failed";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().file, b) << "the user's name, not the temporary's";
  }
  EXPECT_FALSE(fs::exists(a)) << "all or none";
  EXPECT_EQ(read(b), "old b");
  EXPECT_EQ(files_in_dir(), 1u) << "no temporaries left";
}

}  // namespace
}  // namespace rad
