// Every malformed scene under scenes/bad/ fails where its first line says:
// "; expect: [FILE:]LINE:COLUMN: MESSAGE PART", FILE relative to scenes/bad/ (default: itself).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "scene/parser.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

struct Expectation {
  fs::path file;
  int line = 0;
  int column = 0;
  std::string message;
};

const fs::path kBadDir = fs::path(RAD_SOURCE_DIR) / "scenes" / "bad";

std::vector<fs::path> bad_scenes() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(kBadDir)) {
    if (entry.path().extension() == ".des") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool read_expectation(const fs::path& des, Expectation& out) {
  std::ifstream in(des);
  std::string first;
  std::getline(in, first);
  static const std::regex kExpect(R"(^; expect: (?:(.+\.\w+):)?(\d+):(\d+): (.+?)\r?$)");
  std::smatch m;
  if (!std::regex_match(first, m, kExpect)) return false;
  out.file = m[1].matched ? kBadDir / m[1].str() : des;
  out.line = std::stoi(m[2]);
  out.column = std::stoi(m[3]);
  out.message = m[4];
  return true;
}

TEST(BadScenes, ThereIsOneForEveryErrorKind) { EXPECT_GE(bad_scenes().size(), 20u); }

TEST(BadScenes, EachFailsAtTheLocationItsFirstLineNames) {
  for (const fs::path& des : bad_scenes()) {
    SCOPED_TRACE(des.filename().string());
    Expectation want;
    ASSERT_TRUE(read_expectation(des, want)) << "first line is not '; expect: LINE:COL: text'";
    try {
      build_hierarchy(parse_scene_file(des.string()));  // some rules hold for the whole scene
      ADD_FAILURE() << "parsed without error";
    } catch (const Error& e) {
      EXPECT_EQ(fs::path(e.loc().file).lexically_normal(), want.file.lexically_normal())
          << e.what();
      EXPECT_EQ(e.loc().line, want.line) << e.what();
      EXPECT_EQ(e.loc().column, want.column) << e.what();
      EXPECT_NE(e.message().find(want.message), std::string::npos) << e.what();
      std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << "the message is one line";
      EXPECT_EQ(what.rfind(e.loc().file + ":" + std::to_string(want.line) + ":" +
                               std::to_string(want.column) + ": error: ",
                           0),
                0u)
          << what;
    }
  }
}

}  // namespace
}  // namespace rad
