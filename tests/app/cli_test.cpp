// rad's help and usage messages as a user reads them: values named, defaults in words, none of
// the parsing library's notation, and a bad value answered with what was expected.
#include "app/cli.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_rad.h"

namespace {

namespace fs = std::filesystem;

using rad::testing::RadRun;
using rad::testing::run_rad;

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

TEST(Help, NamesEachValueAndItsDefaultWithoutTheParsersNotation) {
  for (const char* mode : {"", "batch ", "serve ", "convert "}) {
    const RadRun r = run_rad(std::string(mode) + "--help");
    ASSERT_EQ(r.code, 0) << mode;
    for (const char* notation : {"{false}", "{true}", " TEXT", " FLOAT", " INT", " UINT",
                                 "REQUIRED", ":NONNEGATIVE", " in ["}) {
      EXPECT_EQ(r.out.find(notation), std::string::npos) << mode << notation << "\n" << r.out;
    }
    for (size_t at = 0, end; at < r.out.size(); at = end + 1) {
      end = std::min(r.out.find('\n', at), r.out.size());
      EXPECT_LE(end - at, 100u) << mode
                                << "a line wider than a terminal: " << r.out.substr(at, end - at);
    }
  }
  const std::string help = run_rad("--help").out;
  for (const char* shown : {"  --roulette FRACTION", "(default 0.01)", "  --threads N",
                            "  --no-packets  ", "  --camera EX,EY,EZ,TX,TY,TZ[,FOV]",
                            "  --backend embree|grid|brute", "(.obj, .ply, .gltf, .glb)"}) {
    EXPECT_NE(help.find(shown), std::string::npos) << shown;
  }
  EXPECT_EQ(help.find("original"), std::string::npos) << "the program rad follows is not a user's";
}

TEST(Help, ABadValueSaysWhatTheOptionExpects) {
  const std::pair<const char*, const char*> cases[] = {
      {"--max-shots five", "rad: --max-shots expects a whole number, got 'five'"},
      {"--converge lots", "rad: --converge expects a number, got 'lots'"},
      {"--roulette five", "rad: --roulette: expects a number, 0 or more, got 'five'"},
      {"--penumbra-rays 100",
       "rad: --penumbra-rays: expects a whole number from 0 to 64, got '100'"},
  };
  for (const auto& [args, said] : cases) {
    const RadRun r = run_rad(std::string(args) + " scene.des out.ply");
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(first_line(r.err), said) << args;
  }
}

// A model is read as a model: the stage names it so.
TEST(Help, AModelIsReadAsAModelFile) {
  const fs::path dir = fs::temp_directory_path() / ("rad_cli_model_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "m.mtl") << "newmtl Floor\nKd 0.5 0.5 0.5\nnewmtl Lamp\nKd 1 1 1\n";
  std::ofstream(dir / "m.obj")
      << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\n"
         "g floor\nusemtl Floor\nf 1 3 2\ng lamp\nusemtl Lamp\nf 4 5 6\n";
  const RadRun r = run_rad("--max-shots 1 --emit 'Lamp=1' " + (dir / "m.obj").string() + " " +
                           (dir / "m.ply").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Reading model file..."), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("Reading description file"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

// rad(1)'s option entries are what --help says of each option (the same definitions, written by
// build/tools/rad-man-options); the man page test checks the rest of the page against --help.
TEST(ManPage, OptionsAreTheHelps) {
  const fs::path page = fs::path(RAD_SOURCE_DIR) / "docs" / "rad.1";
  std::ifstream in(page, std::ios::binary);
  const std::string written{std::istreambuf_iterator<char>(in), {}};
  ASSERT_FALSE(written.empty()) << page;
  EXPECT_TRUE(written == rad::man_page_with_options(written))
      << "docs/rad.1's option entries differ from rad's --help: run "
         "build/tools/rad-man-options docs/rad.1";
  const std::string entries = written.substr(written.find("BEGIN OPTIONS"));
  for (const char* entry : {".BI \\-\\-roulette \" FRACTION\"\n", ".SS Solving\n",
                            ".SS \"rad batch\"\n", ".BR \\-q \", \" \\-\\-quiet\n"}) {
    EXPECT_NE(entries.find(entry), std::string::npos) << entry;
  }
}

}  // namespace
