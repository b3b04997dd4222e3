// The rad executable as a user runs it: exit codes, messages, and what it leaves on disk.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "app/cli.h"
#include "core/error.h"
#include "export/camera.h"
#include "export/false_colour.h"
#include "export/texture_png.h"
#include "export/tonemap.h"
#include "run/write_outputs.h"
#include "run_rad.h"

namespace {

namespace fs = std::filesystem;

using rad::testing::RadRun;
using rad::testing::run_rad;

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
    const std::string file = m[1].matched
                                 ? (kScenes / "bad" / m[1].str()).lexically_normal().string()
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
  const RadRun r = run_rad("-noshadows -minsize 0.1 " +
                           (kScenes / "parallel_squares.des").string() + " " + out.string());
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
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_EQ(r.err.rfind("rad: --backend: unknown visibility backend \"octree\"", 0), 0u) << r.err;
  r = run_rad("--tonemap sepia " + (kScenes / "parallel_squares.des").string() + " /tmp/x.ply");
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_EQ(r.err.rfind("rad: --tonemap: unknown tone curve 'sepia'", 0), 0u) << r.err;
}

TEST(CommandLine, SampleCountsAreSquaresUpTo256AndTheMaximumFollowsTheMinimum) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  RadRun r = run_rad("--samples 15 " + scene + " /tmp/x.ply");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--samples: must be a square number from 1 to 256"), std::string::npos)
      << r.err;
  r = run_rad("--max-samples 289 " + scene + " /tmp/x.ply");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--max-samples: must be a square number from 1 to 256"), std::string::npos)
      << r.err;
  const fs::path stats = fs::temp_directory_path() / "rad_test_samples.json";
  const auto options_of = [&](const std::string& args) {
    const RadRun run = run_rad(args + " -q --max-shots 1 --stats-json " + stats.string() + " " +
                               scene + " /tmp/rad_test_samples.ply");
    EXPECT_EQ(run.code, 0) << run.err;
    const std::string json = read_file(stats);
    const size_t at = json.find("\"max_samples\"");
    return at == std::string::npos ? std::string() : json.substr(at, json.find('\n', at) - at);
  };
  EXPECT_EQ(options_of(""), "\"max_samples\": 64,");
  EXPECT_EQ(options_of("--samples 4 --max-samples 4"), "\"max_samples\": 4,");
  EXPECT_EQ(options_of("--samples 100"), "\"max_samples\": 100,");
  fs::remove(stats);
  fs::remove("/tmp/rad_test_samples.ply");
}

// Reads a binary PLY's header; returns the vertex and face counts and checks the file size.
bool complete_ply(const fs::path& p, size_t* vertices) {
  const std::string data = read_file(p);
  const size_t end = data.find("end_header\n");
  if (end == std::string::npos) return false;
  size_t v = 0, f = 0;
  std::sscanf(data.c_str() + data.find("element vertex"), "element vertex %zu", &v);
  std::sscanf(data.c_str() + data.find("element face"), "element face %zu", &f);
  *vertices = v;
  // 3+3+3 floats + 3 bytes, a float per light group channel; 1 byte + 3 uints per face.
  size_t group_floats = 0;
  for (size_t at = data.find("property float group"); at < end;
       at = data.find("property float group", at + 1))
    ++group_floats;
  return data.size() == end + 11 + v * (39 + 4 * group_floats) + f * 13;
}

TEST(CommandLine, ShardIsIOfNOrTheSlurmArrayTask) {
  int i = -1, n = -1;
  rad::parse_shard("1/3", &i, &n);
  EXPECT_EQ(i, 1);
  EXPECT_EQ(n, 3);
  for (const char* bad : {"3/3", "-1/2", "1/0", "1", "1/2x", "a/b"}) {
    EXPECT_THROW(rad::parse_shard(bad, &i, &n), rad::Error) << bad;
  }
  // sbatch --array=1-4: task ids 1..4, shard ids 0..3.
  setenv("SLURM_ARRAY_TASK_ID", "3", 1);
  setenv("SLURM_ARRAY_TASK_MIN", "1", 1);
  setenv("SLURM_ARRAY_TASK_COUNT", "4", 1);
  rad::parse_shard("slurm", &i, &n);
  EXPECT_EQ(i, 2);
  EXPECT_EQ(n, 4);
  unsetenv("SLURM_ARRAY_TASK_ID");
  EXPECT_THROW(rad::parse_shard("slurm", &i, &n), rad::Error);
  unsetenv("SLURM_ARRAY_TASK_MIN");
  unsetenv("SLURM_ARRAY_TASK_COUNT");
  const RadRun r = run_rad("batch /tmp/rad_test_shard x.des --shard 2/2");
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_NE(r.err.find("--shard: expected I/N with 0 <= I < N"), std::string::npos) << r.err;
}

TEST(CommandLine, BatchWritesTheGoodScenesAndReportsTheBrokenOne) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_batch_" + std::to_string(getpid()));
  fs::remove_all(dir);
  std::string scenes;
  int good = 0;
  for (const auto& e : fs::directory_iterator(kScenes)) {
    if (e.path().extension() == ".des") scenes += " " + e.path().string(), ++good;
  }
  const fs::path broken = kScenes / "bad" / "negative_emission.des";
  const RadRun r = run_rad("batch " + dir.string() + scenes + " " + broken.string() +
                           " --max-shots 40 --size 64x64 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(broken.string() + ":", 0), 0u) << r.err;
  EXPECT_NE(r.out.find(std::to_string(good + 1) + " scenes, 1 failed"), std::string::npos) << r.out;
  for (const auto& e : fs::directory_iterator(kScenes)) {
    if (e.path().extension() != ".des") continue;
    const std::string stem = e.path().stem().string();
    size_t vertices = 0;
    EXPECT_TRUE(complete_ply(dir / (stem + ".ply"), &vertices)) << stem;
    EXPECT_GT(vertices, 0u);
    EXPECT_TRUE(fs::file_size(dir / (stem + ".png")) > 0) << stem;
    EXPECT_NE(read_file(dir / (stem + ".json")).find("\"rad-stats\""), std::string::npos);
  }
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    EXPECT_EQ(e.path().stem().string().find("negative_emission"), std::string::npos) << e.path();
  }
  fs::remove_all(dir);
}

TEST(CommandLine, RendersAnImageWithoutAMeshOutput) {
  const fs::path png = fs::temp_directory_path() / "rad_test_only.png";
  const RadRun r = run_rad("-q --size 32x32 --image " + png.string() + " " +
                           (kScenes / "parallel_squares.des").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(png).rfind("\x89PNG", 0), 0u);
  fs::remove(png);
}

// Each option takes exactly its own values: a repeatable --image before the positionals takes
// one file name, not the scene and the output too.
TEST(CommandLine, ImageBeforeThePositionalsTakesOneValue) {
  const fs::path png = fs::temp_directory_path() / "rad_test_first.png";
  const fs::path png2 = fs::temp_directory_path() / "rad_test_second.png";
  const fs::path ply = fs::temp_directory_path() / "rad_test_after_image.ply";
  const RadRun r = run_rad("-q --size 16x16 --image " + png.string() + " --image " + png2.string() +
                           " " + (kScenes / "parallel_squares.des").string() + " " + ply.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(png).rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(read_file(png2).rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(read_file(ply).rfind("ply\n", 0), 0u);
  for (const fs::path& p : {png, png2, ply}) fs::remove(p);
}

// The original's own command line: .gfo was its output; rad writes Geomview COFF there and says
// so once.
TEST(CommandLine, TheOriginalsGfoOutputIsWrittenAsCoff) {
  const fs::path out = fs::temp_directory_path() / "rad_test_scene5.gfo";
  const RadRun r = run_rad("-noshadows -minsize 0.1 " +
                           (kScenes / "parallel_squares.des").string() + " " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(out).rfind("COFF\n", 0), 0u);
  const std::string note = "writing Geomview COFF there";
  const size_t at = r.out.find(note);
  EXPECT_NE(at, std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(note, at + 1), std::string::npos) << "said once";
  fs::remove(out);
}

// Hostile input ends in one error, never a signal: 20,000 nested Assemblies would overflow the
// parser's stack (SIGSEGV) if the nesting were not bounded.
TEST(CommandLine, TwentyThousandNestedAssembliesEndInOneError) {
  const fs::path des = fs::temp_directory_path() / "rad_test_deep.des";
  {
    std::ofstream f(des);
    f << "\"deep\"\n";
    for (int i = 0; i < 20000; ++i) f << "Object \"a\" Assembly {\n";
    f << "Object \"p\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 1 Data { <0 0 0> <1 0 0> "
         "<0 1 0> } }\n";
    for (int i = 0; i < 20000; ++i) f << "}\n";
  }
  const RadRun r = run_rad("--check " + des.string());
  EXPECT_EQ(r.code, 1) << "an error, not a signal";
  EXPECT_NE(r.err.find(":258:1: error: objects nested more than 256 deep"), std::string::npos)
      << r.err;
  fs::remove(des);
}

// Starts rad in the background (output to /dev/null); returns its pid.
pid_t spawn_rad(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    std::string exe = RAD_BINARY_DIR "/rad";
    argv.push_back(exe.data());
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stdout);
    freopen("/dev/null", "w", stderr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// Waits until `file` exists (the run has reached that point); false after 60 s.
bool wait_for_file(const fs::path& file) {
  for (int i = 0; i < 6000 && !fs::exists(file); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return fs::exists(file);
}

// A run killed with SIGKILL mid-solve, started again with the same command, resumes from its
// checkpoint and writes exactly the mesh of a run never stopped.
TEST(CommandLine, KilledRunResumesFromItsCheckpointToTheSameBytes) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_ckpt_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string scene = (kScenes / "cornell_box.des").string();
  const std::string whole = (dir / "whole.ply").string(), part = (dir / "part.ply").string();
  const std::string ckpt = (dir / "run.ckpt").string();
  ASSERT_EQ(run_rad("-q --max-shots 30 " + scene + " " + whole).code, 0);

  const std::vector<std::string> args{
      "-q", "--max-shots", "30", "--checkpoint", ckpt, "--checkpoint-every", "0", scene, part};
  const pid_t pid = spawn_rad(args);
  ASSERT_TRUE(wait_for_file(ckpt));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "finished before the kill: make the run longer";
  EXPECT_FALSE(fs::exists(part)) << "no output before the end";

  std::string cmd;
  for (const std::string& a : args) cmd += a + " ";
  const RadRun r = run_rad(cmd.substr(3));  // without -q: it says it resumes
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Resuming from checkpoint"), std::string::npos) << r.out;
  EXPECT_TRUE(read_file(whole) == read_file(part)) << "resumed output differs";
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
  }
  fs::remove_all(dir);
}

// Ctrl-C and SIGTERM stop after the shot in progress: the solution so far is written, marked
// partial in the stats, with the checkpoint, and the exit status says which signal (130, 143).
TEST(CommandLine, SigintAndSigtermWriteThePartialSolutionAndTheCheckpoint) {
  for (const int sig : {SIGINT, SIGTERM}) {
    const fs::path dir = fs::temp_directory_path() /
                         ("rad_test_sig_" + std::to_string(getpid()) + "_" + std::to_string(sig));
    fs::create_directories(dir);
    const std::string ckpt = (dir / "run.ckpt").string(), ply = (dir / "out.ply").string();
    const std::string json = (dir / "stats.json").string();
    const pid_t pid =
        spawn_rad({"-q", "--checkpoint", ckpt, "--checkpoint-every", "0", "--stats-json", json,
                   (kScenes / "cornell_box.des").string(), ply});
    ASSERT_TRUE(wait_for_file(ckpt));
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal itself";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_EQ(read_file(ply).rfind("ply\n", 0), 0u);
    const std::string stats = read_file(json);
    EXPECT_NE(stats.find("\"partial\": true"), std::string::npos) << stats.substr(0, 400);
    EXPECT_NE(stats.find("\"stop_reason\": \"interrupted\""), std::string::npos);
    EXPECT_TRUE(fs::exists(ckpt));
    fs::remove_all(dir);
  }
}

// rad --cross-check: the two backends' rays against brute force, the rays the solve cast, the
// vertices and the radiosity, and "agree" with status 0.
TEST(CommandLine, CrossCheckReportsEveryLevelAndAgreesOnABundledScene) {
  const RadRun r =
      run_rad("--cross-check grid --max-shots 3 " + (kScenes / "parallel_squares.des").string());
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  for (const char* line : {"rays, embree against brute force", "rays, grid against brute force",
                           "rays the embree solve cast", "vertices: embree", "radiosity over"}) {
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  }
  EXPECT_NE(r.out.find("\nagree\n"), std::string::npos) << r.out;
  EXPECT_EQ(run_rad("--cross-check nosuch " + (kScenes / "parallel_squares.des").string()).code,
            rad::kExitUsage);
}

// A solve that could outgrow --max-memory is refused before any work, with the estimate and the
// options that change it; nothing is written.
TEST(CommandLine, SolveThatCouldOutgrowTheMemoryLimitIsRefusedWithTheEstimate) {
  const fs::path out = fs::temp_directory_path() / "rad_test_memory.ply";
  fs::remove(out);
  const RadRun r =
      run_rad("--max-memory 1M " + (kScenes / "cornell_box.des").string() + " " + out.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("this solve could need"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--min-size"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(
      run_rad("--max-memory 12Q " + (kScenes / "cornell_box.des").string() + " " + out.string())
          .code,
      rad::kExitUsage);
}

// dir/box.obj and box.mtl: a floor (material White, object floor) under a small square facing
// it (material Lamp, object lamp) that emits nothing until a pattern names it.
void write_lamp_over_floor(const fs::path& dir) {
  std::ofstream(dir / "box.mtl") << "newmtl White\nKd 0.7 0.7 0.7\nnewmtl Lamp\nKd 1 0.9 0.8\n";
  std::ofstream(dir / "box.obj")
      << "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.4 0.9 0.4\nv 0.6 0.9 0.4\n"
         "v 0.6 0.9 0.6\nv 0.4 0.9 0.6\no floor\nusemtl White\nf 1 4 3 2\no lamp\nusemtl Lamp\n"
         "f 5 6 7 8\n";
}

// A model file is a scene: without an emitting material rad says which option makes one emit;
// with --emit it solves and writes.
TEST(CommandLine, SolvesAnObjModelWhoseLampIsNamedByEmit) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_obj_" + std::to_string(getpid()));
  fs::create_directories(dir);
  write_lamp_over_floor(dir);
  const std::string obj = (dir / "box.obj").string(), ply = (dir / "out.ply").string();
  RadRun r = run_rad("-q --max-shots 3 " + obj + " " + ply);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--emit"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ply));
  r = run_rad("-q --max-shots 3 --emit 'La*=5' " + obj + " " + ply);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(ply).rfind("ply\n", 0), 0u);
  fs::remove_all(dir);
}

// A textured OBJ solved to OBJ keeps its texture: the OBJ has coordinates and names its MTL,
// which names the image written beside it, all of them staged with the run's other outputs.
TEST(CommandLine, TexturedModelSolvedToObjWritesItsMtlAndImagesBesideIt) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_obj_uv_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  rad::TextureImage checker;
  checker.levels.resize(1);
  checker.levels[0].width = checker.levels[0].height = 4;
  for (int t = 0; t < 16; ++t) {
    const float c = (t % 2 + t / 4) % 2 ? 0.8f : 0.1f;
    checker.levels[0].texels.push_back(rad::Vec4(c, c, c, 1.0f));
  }
  std::ofstream(dir / "floor.png", std::ios::binary) << rad::encode_png(checker);
  std::ofstream(dir / "box.mtl") << "newmtl Floor\nKd 1 1 1\nmap_Kd floor.png\n"
                                    "newmtl Lamp\nKd 1 0.9 0.8\n";
  std::ofstream(dir / "box.obj")
      << "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.4 0.9 0.4\nv 0.6 0.9 0.4\n"
         "v 0.6 0.9 0.6\nv 0.4 0.9 0.6\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\no floor\nusemtl Floor\n"
         "f 1/1 4/4 3/3 2/2\no lamp\nusemtl Lamp\nf 5 6 7 8\n";
  const fs::path out = dir / "out" / "lit.obj";
  const RadRun r =
      run_rad("-q --max-shots 3 --emit 'La*=5' " + (dir / "box.obj").string() + " " + out.string() +
              " --image " + (dir / "out" / "lit.png").string() + " --size 16x16");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string obj = read_file(out);
  EXPECT_NE(obj.find("mtllib lit.mtl\n"), std::string::npos) << obj.substr(0, 400);
  EXPECT_NE(obj.find("\nvt "), std::string::npos);
  EXPECT_NE(obj.find("usemtl texture0\n"), std::string::npos);
  const std::string mtl = read_file(dir / "out" / "lit.mtl");
  EXPECT_NE(mtl.find("map_Kd lit_texture0.png"), std::string::npos) << mtl;
  int w = 0, h = 0, n = 0;
  const std::string png = read_file(dir / "out" / "lit_texture0.png");
  unsigned char* texels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                                int(png.size()), &w, &h, &n, 4);
  ASSERT_NE(texels, nullptr) << "the texture is a PNG";
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 4);
  stbi_image_free(texels);
  // Exactly the OBJ, its MTL, its image and the render; no temporaries left.
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir / "out"))
    files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"lit.mtl", "lit.obj", "lit.png", "lit_texture0.png"}));
  fs::remove_all(dir);
}

TEST(CommandLine, TwoSidedNamesAModelsMaterialsAndIsRefusedForADescription) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_two_" + std::to_string(getpid()));
  fs::create_directories(dir);
  write_lamp_over_floor(dir);
  const std::string obj = (dir / "box.obj").string();
  RadRun r = run_rad("--check --emit 'La*=5' " + obj);
  EXPECT_NE(r.out.find("Triangles: 4\n"), std::string::npos) << r.out;
  r = run_rad("--check --emit 'La*=5' --two-sided 'Wh*' " + obj);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Triangles: 6\n"), std::string::npos) << "the floor both ways: " << r.out;
  EXPECT_NE(r.out.find("1 two-sided"), std::string::npos) << r.out;
  r = run_rad("--check --emit 'La*=5' --two-sided 'Roof*' " + obj);
  EXPECT_EQ(r.code, rad::kExitInputError);
  EXPECT_NE(r.err.find("--two-sided 'Roof*' matches no material (White, Lamp)"), std::string::npos)
      << r.err;
  r = run_rad("--check --two-sided 'x' " + (kScenes / "cornell_box.des").string());
  EXPECT_EQ(r.code, rad::kExitInputError);
  EXPECT_NE(r.err.find("give the object a TwoSided Yes line"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(CommandLine, HelpListsTheOptions) {
  const RadRun r = run_rad("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt :
       {"--backend", "--threads", "--samples", "--threshold", "--converge", "--max-shots",
        "--time-limit", "--stats-json", "--no-shadows", "--min-size", "--check", "--checkpoint",
        "--checkpoint-every", "--cross-check", "--max-memory", "--emit"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
}

TEST(CommandLine, EachModeRefusesTheOptionsItDoesNotUse) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  const fs::path dir = fs::temp_directory_path() / ("rad_modes_" + std::to_string(getpid()));
  // rad serve solves until stopped and writes no statistics or checkpoints; rad batch names its
  // outputs by --formats; --check solves nothing. Each is a usage error naming the option,
  // before any work (no server started, no folder made).
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"serve " + scene + " --port 0 --check", "--check"},
      {"serve " + scene + " --port 0 --stats-json s.json", "--stats-json"},
      {"serve " + scene + " --port 0 --time-limit 5", "--time-limit"},
      {"serve " + scene + " --port 0 --checkpoint c.ckpt", "--checkpoint"},
      {"serve " + scene + " --port 0 --max-memory 1G", "--max-memory"},
      {"serve " + scene + " --port 0 --cross-check grid", "--cross-check"},
      {"batch " + dir.string() + " " + scene + " --image x.png", "--image"},
      {"batch " + dir.string() + " " + scene + " --checkpoint c.ckpt", "--checkpoint"},
      {"batch " + dir.string() + " " + scene + " --stats-json s.json", "--stats-json"},
      {"batch " + dir.string() + " " + scene + " --check", "--check"},
      {"batch " + dir.string() + " " + scene + " --cross-check grid", "--cross-check"},
      {"batch " + dir.string() + " " + scene + " --port 1", "--port"},
      {scene + " out.ply --port 1", "--port"},
      {scene + " out.ply --formats ply", "--formats"},
      {"--check " + scene + " --checkpoint c.ckpt", "--checkpoint"},
  };
  for (const auto& [args, option] : refused) {
    const RadRun r = run_rad(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(r.out.find("rad serve: http"), std::string::npos) << args;
  }
  EXPECT_FALSE(fs::exists(dir));
  // What they do take.
  const RadRun serve = run_rad("serve --help"), batch = run_rad("batch --help");
  for (const char* opt : {"--port", "--host", "--output", "--image", "--max-shots", "--converge",
                          "--backend", "--threads", "--emit", "--exposure"}) {
    EXPECT_NE(serve.out.find(opt), std::string::npos) << "serve " << opt;
  }
  for (const char* opt : {"--formats", "--shard", "--max-shots", "--time-limit", "--max-memory",
                          "--backend", "--camera", "--size", "--emit"}) {
    EXPECT_NE(batch.out.find(opt), std::string::npos) << "batch " << opt;
  }
}

TEST(CommandLine, ConvertTakesAModelWithoutLightsToADescriptionAndBack) {
  const fs::path dir = fs::temp_directory_path() / ("rad_convert_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "room.mtl") << "newmtl Wall\nKd 0.7 0.7 0.7\n";
  std::ofstream(dir / "room.obj")
      << "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng wall\nusemtl Wall\nf 1 2 3 4\n";
  RadRun r = run_rad("convert " + (dir / "room.obj").string() + " " + (dir / "room.des").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 triangles"), std::string::npos) << r.out;
  r = run_rad("--check " + (dir / "room.des").string());
  EXPECT_EQ(r.code, 0) << r.err;
  r = run_rad("convert " + (dir / "room.des").string() + " " + (dir / "room.glb").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "room.glb"));
  // Solving it still asks for a light, naming --emit.
  r = run_rad((dir / "room.glb").string() + " " + (dir / "room.ply").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--emit"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(CommandLine, ConvertRefusesAnUnknownFormatAndTheSolversOptions) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  const fs::path out =
      fs::temp_directory_path() / ("rad_convert_" + std::to_string(getpid()) + ".fbx");
  RadRun r = run_rad("convert " + scene + " " + out.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(".fbx"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run_rad("convert --max-shots 3 " + scene + " /tmp/x.des");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("max-shots"), std::string::npos) << r.err;
}

TEST(CommandLine, VersionIsTheProjectsAndGoesIntoTheStats) {
  for (const char* mode : {"", "batch ", "serve ", "convert "}) {
    const RadRun r = run_rad(std::string(mode) + "--version");
    EXPECT_EQ(r.code, rad::kExitDone) << mode << r.err;
    EXPECT_EQ(r.out, "rad " RAD_VERSION "\n") << mode;
  }
  const fs::path stats = fs::temp_directory_path() / "rad_test_version.json";
  const RadRun r = run_rad("-q --max-shots 1 --stats-json " + stats.string() + " " +
                           (kScenes / "parallel_squares.des").string() + " --image " +
                           (fs::temp_directory_path() / "rad_test_version.png").string());
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string json = read_file(stats);
  EXPECT_NE(json.find("\"rad_version\": \"" RAD_VERSION "\""), std::string::npos);
  // The camera the image was rendered through, as --camera takes it.
  const size_t at = json.find("\"camera\": \"");
  ASSERT_NE(at, std::string::npos) << json;
  const size_t from = at + 11, to = json.find('"', from);
  EXPECT_NO_THROW(rad::parse_camera(json.substr(from, to - from))) << json.substr(from, to - from);
  EXPECT_NE(json.find("\"objects\": ["), std::string::npos);
  fs::remove(stats);
  fs::remove(fs::temp_directory_path() / "rad_test_version.png");
}

TEST(CommandLine, EditDistanceCountsDroppedAddedChangedAndSwappedLetters) {
  EXPECT_EQ(rad::edit_distance("--max-shot", "--max-shots"), 1u);
  EXPECT_EQ(rad::edit_distance("--smaples", "--samples"), 1u);
  EXPECT_EQ(rad::edit_distance("--treshold", "--threshold"), 1u);
  EXPECT_EQ(rad::edit_distance("--port", "--size"), 4u);
  EXPECT_EQ(rad::edit_distance("", "abc"), 3u);
  EXPECT_EQ(rad::edit_distance("abc", "abc"), 0u);
  const std::vector<std::string> names{"--threads", "--threshold", "--samples", "-q", "--emit"};
  EXPECT_EQ(rad::nearest_option("--thread", names), "--threads");
  EXPECT_EQ(rad::nearest_option("--thresold", names), "--threshold");
  EXPECT_EQ(rad::nearest_option("--emitt", names), "--emit");
  EXPECT_EQ(rad::nearest_option("-x", names), std::nullopt) << "one letter: anything is near";
  EXPECT_EQ(rad::nearest_option("--colour", names), std::nullopt);
}

// An unknown option is named first, with the nearest of the mode's own options, or the mode
// that takes it; the status is the usage error's, before any work.
TEST(CommandLine, UnknownOptionIsNamedFirstWithWhatWasMeant) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  const fs::path out = fs::temp_directory_path() / "rad_test_unknown.ply";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--max-shot 5 " + scene + " " + out.string(),
       "rad: unknown option '--max-shot'; did you mean '--max-shots'?\n"},
      {scene + " " + out.string() + " --smaples=4",
       "rad: unknown option '--smaples'; did you mean '--samples'?\n"},
      {"batch /tmp/rad_test_unknown_dir " + scene + " --fromats ply",
       "rad batch: unknown option '--fromats'; did you mean '--formats'?\n"},
      {"serve " + scene + " --prot 8080",
       "rad serve: unknown option '--prot'; did you mean '--port'?\n"},
      {"convert " + scene + " /tmp/x.des --emitt 'a=1'",
       "rad convert: unknown option '--emitt'; did you mean '--emit'?\n"},
      {"--colourful " + scene + " " + out.string(), "rad: unknown option '--colourful'\n"},
      {"serve " + scene + " --stats-json s.json",
       "rad serve: unknown option '--stats-json' (rad [options] SCENE OUTPUT takes it; rad serve "
       "does not)\n"},
      {scene + " " + out.string() + " extra.ply", "rad: unexpected argument 'extra.ply'\n"},
  };
  for (const auto& [args, first_line] : cases) {
    const RadRun r = run_rad(args);
    EXPECT_EQ(r.code, rad::kExitUsage) << args;
    EXPECT_EQ(r.err.substr(0, r.err.find('\n') + 1), first_line) << args;
    EXPECT_NE(r.err.find("--help' lists the options"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists("/tmp/rad_test_unknown_dir"));
}

// 0 done, 1 input error, 2 usage error (130 and 143 for signals:
// SigintAndSigtermWriteThePartialSolutionAndTheCheckpoint); every mode's help lists them.
TEST(CommandLine, ExitStatusTellsAUsageErrorFromAnInputError) {
  EXPECT_EQ(run_rad("").code, rad::kExitUsage);
  EXPECT_EQ(run_rad("batch").code, rad::kExitUsage);
  EXPECT_EQ(run_rad("--threads many a.des b.ply").code, rad::kExitUsage);
  const RadRun missing = run_rad("/tmp/rad_test_no_such_scene.des /tmp/x.ply");
  EXPECT_EQ(missing.code, rad::kExitInputError);
  EXPECT_EQ(missing.err.rfind("/tmp/rad_test_no_such_scene.des", 0), 0u) << missing.err;
  EXPECT_EQ(run_rad("--check " + (kScenes / "parallel_squares.des").string()).code, rad::kExitDone);
  for (const char* mode : {"", "batch ", "serve ", "convert "}) {
    const RadRun r = run_rad(std::string(mode) + "--help");
    EXPECT_EQ(r.code, rad::kExitDone);
    for (const char* line :
         {"Exit status:", "  0    done", "  1    input error", "  2    usage error"}) {
      EXPECT_NE(r.out.find(line), std::string::npos) << mode << line;
    }
  }
  EXPECT_NE(run_rad("--help").out.find("  130  stopped by Ctrl-C (SIGINT), 143 by SIGTERM"),
            std::string::npos);
  EXPECT_NE(run_rad("batch --help").out.find("any scene that failed"), std::string::npos);
}

// rad batch --help, rad serve --help and rad convert --help describe that mode alone, with an
// example, in the user's words.
TEST(CommandLine, EachModesHelpShowsThatModeOnlyWithAnExample) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> modes = {
      {"", {"rad batch OUTDIR", "rad serve SCENE", "rad convert IN OUT"}},
      {"batch ", {"rad serve", "rad convert", "--cross-check", "--stats-json"}},
      {"serve ", {"rad batch", "rad convert", "--formats", "--time-limit"}},
      {"convert ", {"rad batch", "rad serve", "--max-shots", "--backend"}},
  };
  for (const auto& [mode, not_here] : modes) {
    const RadRun r = run_rad(mode + "--help");
    EXPECT_EQ(r.code, 0) << mode;
    EXPECT_NE(r.out.find("Example"), std::string::npos) << mode;
    EXPECT_NE(r.out.find("rad " + mode), std::string::npos) << mode;
    for (const char* jargon : {"SPEC", "§", "EQ "}) {
      EXPECT_EQ(r.out.find(jargon), std::string::npos) << mode << jargon;
    }
    if (mode.empty()) {
      for (const std::string& other : not_here) EXPECT_NE(r.out.find(other), std::string::npos);
    } else {
      for (const std::string& other : not_here) {
        EXPECT_EQ(r.out.find(other), std::string::npos) << mode << other;
      }
    }
  }
}

// -q: errors only. A scene that warns (a degenerate triangle) says nothing at all under -q.
TEST(CommandLine, QuietPrintsErrorsOnlyNotWarnings) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_quiet_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "warns.des")
      << "\"warns\"\nObject \"p\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 1 Data {\n"
         "<0 0 0> <1 0 0> <0 1 0>  <0 0 0> <1 0 0> <2 0 0> } }\n";
  const std::string args =
      "--max-shots 1 " + (dir / "warns.des").string() + " " + (dir / "out.ply").string();
  RadRun r = run_rad(args);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: dropped 1 degenerate"), std::string::npos) << r.err;
  r = run_rad("-q " + args);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
  r = run_rad("-q --check " + (dir / "warns.des").string() + " --backend nosuch");
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_NE(r.err, "") << "errors still print";
  fs::remove_all(dir);
}

// Every output (mesh, images, statistics, checkpoint) is checked before the scene is even read,
// so a typo in a folder costs no solve; and the outputs appear together or not at all.
TEST(CommandLine, EveryOutputIsCheckedBeforeTheSolveAndWrittenAllOrNone) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_outputs_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = (kScenes / "cornell_box.des").string();
  const std::string ply = (dir / "t.ply").string(), missing = (dir / "nodir").string();
  for (const std::string& bad :
       {missing + "/t.ply", ply + " --image " + missing + "/t.png",
        ply + " --stats-json " + missing + "/s.json", ply + " --checkpoint " + missing + "/c.ckpt",
        ply + " --image " + dir.string() + ".png --image " + missing + "/t.hdr"}) {
    const RadRun r = run_rad(scene + " " + bad);
    EXPECT_EQ(r.code, rad::kExitInputError) << bad;
    EXPECT_EQ(r.err.rfind(missing + "/", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("does not exist; create it or give another path"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.out.find("Reading description file"), std::string::npos) << "no work: " << bad;
    EXPECT_FALSE(fs::exists(ply)) << "none of the outputs: " << bad;
    EXPECT_FALSE(fs::exists(dir.string() + ".png")) << bad;
  }
  const RadRun r = run_rad(scene + " " + dir.string() + " --image " + (dir / "t.png").string());
  EXPECT_EQ(r.code, rad::kExitInputError);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
  // All of them when they can be written, and no temporaries.
  const RadRun ok =
      run_rad("-q --max-shots 2 --size 16x16 " + scene + " " + ply + " --image " +
              (dir / "t.png").string() + " --stats-json " + (dir / "s.json").string());
  EXPECT_EQ(ok.code, 0) << ok.err;
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    ++files;
  }
  EXPECT_EQ(files, 3u);
  fs::remove_all(dir);
}

// A scene with no light has nothing to solve: an error saying how to light it, unless
// --max-shots 0 asks for the unlit scene (emission only).
TEST(CommandLine, ASceneWithoutLightIsRefusedUnlessOnlyTheEmissionIsAsked) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_dark_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string des = (dir / "dark.des").string(), ply = (dir / "dark.ply").string();
  std::ofstream(des) << "\"dark\"\nObject \"p\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 "
                        "Data { <0 0 0> <1 0 0> <0 1 0> } }\n";
  RadRun r = run_rad(des + " " + ply);
  EXPECT_EQ(r.code, rad::kExitInputError);
  EXPECT_EQ(r.err.rfind(des + ": error: nothing in this scene emits light", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("Emission"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-shots 0"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ply));
  r = run_rad("-q --max-shots 0 " + des + " " + ply);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(ply).rfind("ply\n", 0), 0u);
  EXPECT_EQ(run_rad("--check " + des).code, 0) << "--check only reads it";
  // A model without lamps likewise: refused with the --emit hint, written unlit with
  // --max-shots 0, summarised by --check.
  const std::string obj = (dir / "dark.obj").string();
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  r = run_rad(obj + " " + ply);
  EXPECT_EQ(r.code, rad::kExitInputError);
  EXPECT_NE(r.err.find("--emit"), std::string::npos) << r.err;
  fs::remove(ply);
  r = run_rad("-q --max-shots 0 " + obj + " " + ply);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(ply));
  EXPECT_EQ(run_rad("--check " + obj).code, 0);
  fs::remove_all(dir);
}

// --emit names a model's materials; given to a description it is refused, not ignored.
TEST(CommandLine, EmitGivenToADescriptionIsRefused) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  const fs::path dir = fs::temp_directory_path() / ("rad_test_emit_" + std::to_string(getpid()));
  for (const std::string& args : {"--emit 'Lamp=5' " + scene + " " +
                                      (fs::temp_directory_path() / "rad_test_emit.ply").string(),
                                  "--check --emit 'Lamp=5' " + scene,
                                  "batch " + dir.string() + " " + scene + " --emit 'Lamp=5'"}) {
    const RadRun r = run_rad(args);
    EXPECT_EQ(r.code, rad::kExitInputError) << args;
    EXPECT_NE(r.err.find("--emit names the materials of a model"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Emission"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "rad_test_emit.ply"));
}

}  // namespace

namespace {

// A description lit by a Light object alone: rad solves it, prints each object's illuminance
// and writes the light arriving into the PLY and the stats.
TEST(CommandLine, ADescriptionLitByALightPrintsItsObjectsIlluminance) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_light_" + std::to_string(getpid()));
  fs::create_directories(dir);
  {
    std::ofstream des(dir / "lamp.des");
    des << "\"lamp over a floor\"\n"
           "Object \"floor\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0\n"
           "  Data { <-2 0 -2> <-2 0 2> <2 0 2>  <-2 0 -2> <2 0 2> <2 0 -2> } }\n"
           "Object \"lamp\" Light { Type Point Position <0 2 0> Intensity 400 }\n";
  }
  const RadRun r = run_rad((dir / "lamp.des").string() + " " + (dir / "lamp.ply").string() +
                           " --stats-json " + (dir / "lamp.json").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Illuminance"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("floor"), std::string::npos) << r.out;
  const std::string json = read_file(dir / "lamp.json");
  EXPECT_NE(json.find("\"lights\": 1"), std::string::npos);
  // 400 cd 2 m straight above: 100 lx at the floor's centre, the most it gets.
  const size_t at = json.find("\"max\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_NEAR(std::stod(json.substr(at + 7)), 100.0, 0.1) << json;
  const std::string ply = read_file(dir / "lamp.ply");
  EXPECT_NE(ply.find("property float irradiance_r"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace

namespace {

// A PFM image as rad writes it: "PF", width height, -1 (little-endian), rows bottom up.
struct Pfm {
  int width = 0, height = 0;
  std::vector<float> rgb;  // top row first
  std::array<float, 3> at(int x, int y) const {
    const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

Pfm read_pfm(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::string magic;
  float scale = 0.0f;
  Pfm img;
  f >> magic >> img.width >> img.height >> scale;
  f.get();
  if (magic != "PF" || img.width <= 0 || img.height <= 0) return {};
  std::vector<float> rows(3 * size_t(img.width) * size_t(img.height));
  f.read(reinterpret_cast<char*>(rows.data()), std::streamsize(rows.size() * sizeof(float)));
  img.rgb.resize(rows.size());
  const size_t row = 3 * size_t(img.width);
  for (int y = 0; y < img.height; ++y)
    std::copy_n(rows.begin() + std::ptrdiff_t(size_t(img.height - 1 - y) * row), row,
                img.rgb.begin() + std::ptrdiff_t(size_t(y) * row));
  return img;
}

// --false-colour lux: a black floor under a 500 lx sun straight above shows, on a scale to
// 1000 lx, the palette's colour halfway up, in rad's images and rad batch's; a legend strip is
// added on the left. Its options are checked before any work.
TEST(CommandLine, FalseColourShowsAKnownIlluminanceInThePalettesColourForIt) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_false_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "sun.des")
      << "\"sun on a floor\"\n"
         "Object \"floor\" Pure { Reflectivity 0 Color <1 1 1> Emission 0\n"
         "  Data { <-2 0 -2> <-2 0 2> <2 0 2>  <-2 0 -2> <2 0 2> <2 0 -2> } }\n"
         "Object \"sun\" Light { Type Directional Direction <0 -1 0> Intensity 500 }\n";
  const std::string view = " --camera 0,3,-0.5,0,0,0,30 --size 64x64 --false-colour lux";
  const std::string scale = " --false-colour-max 1000";
  RadRun r =
      run_rad((dir / "sun.des").string() + " --image " + (dir / "sun.pfm").string() + view + scale);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("False colour: illuminance 0 to 1000 lx"), std::string::npos) << r.out;
  const rad::Vec3 half = rad::false_colour_display(0.5f);
  const auto expect_half = [&](const fs::path& image) {
    const Pfm img = read_pfm(image);
    ASSERT_EQ(img.height, 64) << image;
    ASSERT_GT(img.width, 64) << "no legend strip in " << image;
    const std::array<float, 3> centre = img.at(img.width - 32, 32);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(rad::srgb_encode(centre[size_t(k)]), half[k], 1e-3) << image << " channel " << k;
    }
  };
  expect_half(dir / "sun.pfm");
  r = run_rad("batch " + (dir / "batch").string() + " " + (dir / "sun.des").string() +
              " --formats pfm -q" + view + scale);
  ASSERT_EQ(r.code, 0) << r.err;
  expect_half(dir / "batch" / "sun.pfm");
  // Without --false-colour-max the scale tops at a round number above the floor's 500 lx.
  r = run_rad((dir / "sun.des").string() + " --image " + (dir / "auto.pfm").string() + view);
  EXPECT_NE(r.out.find("illuminance 0 to 500 lx"), std::string::npos) << r.out;

  const std::vector<std::pair<std::string, std::string>> refused = {
      {" --image x.png --false-colour rgb", "--false-colour"},
      {" --image x.png --false-colour-max 100", "--false-colour lux"},
      {" --image x.png --false-colour lux --false-colour-max -5", "--false-colour-max"},
      {" --image x.png --false-colour lux --false-colour-log 20", "--false-colour-log"},
  };
  for (const auto& [args, says] : refused) {
    r = run_rad((dir / "sun.des").string() + args);
    EXPECT_EQ(r.code, rad::kExitUsage) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
  }
  fs::remove_all(dir);
}

}  // namespace

namespace {

// --unit: a description in centimetres, its lamp 200 units = 2 m up, is reported in lux, square
// metres and lumens; the value is checked before any work; a glTF model is metres anyway.
TEST(CommandLine, UnitGivesTheMetresOfASceneUnitForLuxAreasAndLumens) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_unit_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "cm.des")
      << "\"lamp over a floor, centimetres\"\n"
         "Object \"floor\" Pure { Reflectivity 0 Color <1 1 1> Emission 0\n"
         "  Data { <-200 0 -200> <-200 0 200> <200 0 200>  <-200 0 -200> <200 0 200> "
         "<200 0 -200> } }\n"
         "Object \"lamp\" Light { Type Point Position <0 200 0> Intensity 400 }\n";
  RadRun r = run_rad((dir / "cm.des").string() + " " + (dir / "cm.ply").string() +
                     " --unit 0.01 -q --stats-json " + (dir / "cm.json").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string json = read_file(dir / "cm.json");
  const auto number = [&](const std::string& key) {
    const size_t at = json.find("\"" + key + "\": ");
    return at == std::string::npos ? -1.0 : std::stod(json.substr(at + key.size() + 4));
  };
  EXPECT_NEAR(number("max"), 100.0, 0.1) << json;  // 400 cd at 2 m
  EXPECT_NEAR(number("area"), 16.0, 1e-3) << json;
  EXPECT_NEAR(number("lumens"), 4.0 * M_PI * 400.0, 1.0) << json;
  EXPECT_EQ(number("unit"), 0.01) << json;

  for (const char* bad : {"0", "-1", "nan", "metres"}) {
    r = run_rad((dir / "cm.des").string() + " x.ply --unit " + bad);
    EXPECT_EQ(r.code, rad::kExitUsage) << bad;
    EXPECT_NE(r.err.find("--unit"), std::string::npos) << bad << ": " << r.err;
  }
  // A glTF model's lengths are metres by the glTF specification: --unit is ignored, saying so.
  std::ofstream(dir / "wall.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  r = run_rad("convert -q " + (dir / "wall.obj").string() + " " + (dir / "wall.glb").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_rad("--check " + (dir / "wall.glb").string() + " --unit 0.01");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find((dir / "wall.glb").string() + ": warning: --unit 0.01 is ignored"),
            std::string::npos)
      << r.err;
  fs::remove_all(dir);
}

}  // namespace

namespace {

// --stage lights a model with no light of its own: it solves, says what it staged and frames
// it; given to a description it is refused (it places its own floor and lights); --sun takes
// ELEVATION,AZIMUTH or nothing.
TEST(CommandLine, StageLightsAModelAndIsRefusedForADescription) {
  const fs::path dir = fs::temp_directory_path() / ("rad_test_stage_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  const std::string obj = (dir / "quad.obj").string(), ply = (dir / "out.ply").string();
  for (const std::string flags : {"--stage", "--sun", "--stage --sun 30,60"}) {
    const RadRun r = run_rad(obj + " " + ply + " " + flags + " --image " +
                             (dir / "o.png").string() + " --size 64x64 --render preview");
    EXPECT_EQ(r.code, 0) << flags << ": " << r.err;
    EXPECT_NE(r.out.find("Stage: floor "), std::string::npos) << r.out;
    EXPECT_NE((r.out + r.err).find("converged"), std::string::npos) << r.out << r.err;
    EXPECT_EQ(r.out.find("sun at") != std::string::npos, flags != "--stage") << r.out;
    EXPECT_TRUE(fs::exists(dir / "o.png"));
  }
  // rad convert writes the staged scene as a description to edit.
  const RadRun c = run_rad("convert " + obj + " " + (dir / "staged.des").string() + " --sun");
  EXPECT_EQ(c.code, 0) << c.err;
  const std::string des = read_file(dir / "staged.des");
  EXPECT_NE(des.find("\"stage floor\""), std::string::npos) << des;
  EXPECT_NE(des.find("\"stage sun\""), std::string::npos) << des;

  const RadRun bad = run_rad("--sun " + obj + " " + ply);  // the scene taken for its angles
  EXPECT_EQ(bad.code, rad::kExitUsage);
  EXPECT_NE(bad.err.find("ELEVATION,AZIMUTH"), std::string::npos) << bad.err;

  const std::string scene = (kScenes / "parallel_squares.des").string();
  for (const std::string& args :
       {"--stage " + scene + " " + ply, "--check --sun " + scene,
        "batch " + (dir / "batch").string() + " " + scene + " --stage",
        "convert " + scene + " " + (dir / "x.obj").string() + " --stage"}) {
    const RadRun r = run_rad(args);
    EXPECT_EQ(r.code, rad::kExitInputError) << args;
    EXPECT_NE(r.err.find("--stage sets a model"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
  fs::remove_all(dir);
}

TEST(CommandLine, ImagesRenderByFinalGatherOrPreviewOverABackgroundOrTransparent) {
  const std::string scene = (kScenes / "parallel_squares.des").string();
  const fs::path dir = fs::temp_directory_path() / ("rad_render_" + std::to_string(getpid()));
  fs::create_directories(dir);
  RadRun r = run_rad("--render sketch " + scene + " " + (dir / "x.ply").string());
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_NE(r.err.find("--render: expected final or preview, got sketch"), std::string::npos)
      << r.err;
  r = run_rad("--background 1,2 " + scene + " " + (dir / "x.ply").string());
  EXPECT_EQ(r.code, rad::kExitUsage);
  EXPECT_NE(r.err.find("--background: expected R,G,B"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.ply"));
  // The squares seen from afar, the void around them transparent: RGBA, some pixels clear.
  r = run_rad("-q --size 40x40 --camera 0,0,-10,0,0,0,60 --background transparent --image " +
              (dir / "t.png").string() + " " + scene + " " + (dir / "t.ply").string());
  ASSERT_EQ(r.code, 0) << r.err;
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load((dir / "t.png").string().c_str(), &w, &h, &n, 0);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(n, 4);
  EXPECT_EQ(data[3], 0);  // the top left corner sees nothing
  stbi_image_free(data);
  r = run_rad("-q --size 40x40 --render preview --image " + (dir / "p.png").string() + " " + scene +
              " " + (dir / "p.ply").string());
  EXPECT_EQ(r.code, 0) << r.err;
  fs::remove_all(dir);
}

// --group-images: beside each image, one per light group through the same camera and exposure;
// in linear images the groups add up to the whole (both sides solved to the same convergence,
// so within a few tenths of a percent). A scene of one group writes no more images and says so.
TEST(CommandLine, GroupImagesAddUpToTheWholeImage) {
  const fs::path dir = fs::temp_directory_path() / ("rad_group_images_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string scene = (kScenes / "cornell_box_groups.des").string();
  for (const std::string render : {"final", "preview"}) {
    const fs::path image = dir / (render + ".pfm");
    // Elements of at least 20 (in a box of 556): the test's time goes to the images.
    const RadRun r = run_rad(
        "-q --min-size 20 --size 32x32 --pixel-samples 1 --group-images --render " + render +
        " --image " + image.string() + " " + scene + " " + (dir / "g.ply").string());
    ASSERT_EQ(r.code, 0) << r.err;
    const Pfm whole = read_pfm(image);
    const Pfm panel = read_pfm(dir / (render + ".panel.pfm"));
    const Pfm lamp = read_pfm(dir / (render + ".lamp.pfm"));
    ASSERT_EQ(whole.rgb.size(), 32u * 32u * 3u);
    ASSERT_EQ(panel.rgb.size(), whole.rgb.size());
    ASSERT_EQ(lamp.rgb.size(), whole.rgb.size());
    double diff = 0.0, total = 0.0, panel_sum = 0.0, lamp_sum = 0.0;
    for (size_t i = 0; i < whole.rgb.size(); ++i) {
      diff += std::abs(double(whole.rgb[i]) - panel.rgb[i] - lamp.rgb[i]);
      total += std::abs(double(whole.rgb[i]));
      panel_sum += panel.rgb[i], lamp_sum += lamp.rgb[i];
    }
    EXPECT_LT(diff / total, 5e-3) << render;
    EXPECT_GT(panel_sum, 0.01 * total) << render;  // each group lights the box
    EXPECT_GT(lamp_sum, 0.01 * total) << render;
  }
  const RadRun one =
      run_rad("--max-shots 5 --size 16x16 --group-images --image " + (dir / "one.png").string() +
              " " + (kScenes / "cornell_box.des").string() + " " + (dir / "one.ply").string());
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_NE(one.err.find("--group-images: the scene has no two light groups"), std::string::npos)
      << one.err;
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2u * 3u + 1u + 2u);  // final, preview: whole, panel, lamp; g.ply; one.*
  fs::remove_all(dir);
}

TEST(CommandLine, GroupImagesAreNamedByTheirGroupsOnce) {
  EXPECT_EQ(rad::group_image_paths("out/box.png", {"panel", "Desk lamp", "", "Desk/lamp"}),
            (std::vector<std::string>{"out/box.panel.png", "out/box.Desk_lamp.png",
                                      "out/box.group2.png", "out/box.group3.png"}));
  EXPECT_EQ(rad::group_image_paths("a.b/box", {"x"}), (std::vector<std::string>{"a.b/box.x"}));
}

}  // namespace
