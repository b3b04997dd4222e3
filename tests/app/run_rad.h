// Runs the rad executable as a user does, for the tests of what it prints and returns.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace rad::testing {

struct RadRun {
  int code;
  std::string out, err;
};

/// `rad ARGS` through the shell: its exit status (-1 if it did not exit), standard output and
/// standard error.
inline RadRun run_rad(const std::string& args) {
  const std::filesystem::path err_file =
      std::filesystem::temp_directory_path() / ("rad_test_err_" + std::to_string(getpid()));
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
  std::filesystem::remove(err_file);
  return r;
}

}  // namespace rad::testing
