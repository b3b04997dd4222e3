// The rad executable as a user runs it: exit codes, messages, and what it leaves on disk.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace {

namespace fs = std::filesystem;

struct RadRun {
  int code;
  std::string out, err;
};

RadRun run_rad(const std::string& args) {
  const fs::path err_file = fs::temp_directory_path() / ("rad_test_err_" + std::to_string(getpid()));
  const std::string cmd = std::string(RAD_BINARY_DIR "/rad ") + args + " 2>" + err_file.string();
  RadRun r{};
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  fs::remove(err_file);
  return r;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

const fs::path kScenes = fs::path(RAD_SOURCE_DIR) / "scenes";

TEST(CommandLine, CheckSucceedsOnEveryBundledScene) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".des") continue;
    const RadRun r = run_rad("--check " + entry.path().string());
    EXPECT_EQ(r.code, 0) << entry.path() << "\n" << r.err;
    EXPECT_NE(r.out.find("Triangles:"), std::string::npos) << r.out;
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

// Each file in scenes/bad/ starts with "; expect: [FILE:]LINE:COLUMN: text".
TEST(CommandLine, CheckFailsOnEveryBrokenSceneWithFileLineAndColumn) {
  int checked = 0;
  const std::regex expect_re(R"(^; expect: (?:([^:]+):)?(\d+):(\d+): (.*)$)");
  for (const auto& entry : fs::directory_iterator(kScenes / "bad")) {
    if (entry.path().extension() != ".des") continue;
    std::ifstream f(entry.path());
    std::string first;
    std::getline(f, first);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(first, m, expect_re)) << entry.path();
    const std::string file = m[1].matched ? (kScenes / "bad" / m[1].str()).lexically_normal().string()
                                          : entry.path().string();
    const std::string where = file + ":" + m[2].str() + ":" + m[3].str() + ": error: ";
    const RadRun r = run_rad("--check " + entry.path().string());
    EXPECT_NE(r.code, 0) << entry.path();
    EXPECT_EQ(r.err.rfind(where, 0), 0u) << "expected " << where << "\ngot " << r.err;
    EXPECT_NE(r.err.find(m[4].str()), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

TEST(CommandLine, FailedRunLeavesAnExistingOutputUnchanged) {
  const fs::path out = fs::temp_directory_path() / "rad_test_keep.ply";
  const std::string before = "precious bytes\n";
  std::ofstream(out, std::ios::binary) << before;
  const RadRun r = run_rad((kScenes / "bad" / "unknown_keyword.des").string() + " " + out.string());
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(read_file(out), before);
  for (const auto& e : fs::directory_iterator(out.parent_path())) {
    EXPECT_EQ(e.path().string().find("rad_test_keep.ply.tmp"), std::string::npos) << e.path();
  }
  fs::remove(out);
}

TEST(CommandLine, SolvesWithTheOriginalsFlagsAndWritesAPly) {
  const fs::path out = fs::temp_directory_path() / "rad_test_squares.ply";
  const RadRun r = run_rad("-noshadows -minsize 0.1 " + (kScenes / "parallel_squares.des").string() +
                        " " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* stage : {"Reading description file...", "Initializing...",
                            "Starting Computation", "Writing results in file"}) {
    EXPECT_NE(r.out.find(stage), std::string::npos) << stage;
  }
  EXPECT_NE(r.out.find("Ray-Tracing Statistics:"), std::string::npos);
  EXPECT_NE(r.out.find("Number of rays shot:          0"), std::string::npos) << "-noshadows";
  EXPECT_EQ(read_file(out).rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  fs::remove(out);
}

TEST(CommandLine, RejectsAnUnknownBackendOrFormatBeforeWorking) {
  const fs::path out = fs::temp_directory_path() / "rad_test_never.xyz";
  RadRun r = run_rad((kScenes / "parallel_squares.des").string() + " " + out.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("unknown output format"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run_rad("--backend octree " + (kScenes / "parallel_squares.des").string() + " /tmp/x.ply");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind("error: unknown visibility backend \"octree\"", 0), 0u) << r.err;
  r = run_rad("--tonemap sepia " + (kScenes / "parallel_squares.des").string() + " /tmp/x.ply");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind("error: unknown tone curve 'sepia'", 0), 0u) << r.err;
}

TEST(CommandLine, HelpListsTheOptions) {
  const RadRun r = run_rad("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--backend", "--threads", "--samples", "--threshold", "--converge",
                          "--max-shots", "--time-limit", "--stats-json", "--no-shadows",
                          "--min-size", "--check"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
}

}  // namespace
