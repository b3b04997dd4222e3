// The Khronos glTF validator (npm package gltf-validator, run by gltf_validate.js through node)
// for tests that write glTF; absent on machines without node or the package.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace rad::testing {

struct ValidatorRun {
  std::string skipped;  // why it did not run, or empty
  int status = 0;       // gltf_validate.js's exit status: 0 no errors
  std::string report;   // one line per file ("FILE: N errors, ..."), then its issues
};

/// Validates `files`, the report kept in `log`.
inline ValidatorRun run_gltf_validator(const std::vector<std::string>& files,
                                       const std::filesystem::path& log) {
  namespace fs = std::filesystem;
  ValidatorRun r;
  if (std::system("command -v node > /dev/null 2>&1") != 0) {
    r.skipped = "node is not installed: the glTF validator cannot run";
    return r;
  }
  std::string node_path;
  for (const fs::path& d :
       {fs::path(RAD_BINARY_DIR) / "npm" / "node_modules",
        fs::path(RAD_SOURCE_DIR) / "build" / "npm" / "node_modules",
        fs::path("/usr/local/lib/node_modules"), fs::path("/usr/lib/node_modules")}) {
    if (fs::exists(d / "gltf-validator")) node_path += (node_path.empty() ? "" : ":") + d.string();
  }
  if (node_path.empty()) {
    r.skipped =
        "the npm package gltf-validator is not installed; install it with: npm install "
        "--prefix " RAD_BINARY_DIR "/npm gltf-validator";
    return r;
  }
  std::string cmd =
      "NODE_PATH='" + node_path + "' node '" RAD_SOURCE_DIR "/tests/export/gltf_validate.js'";
  for (const std::string& f : files) cmd += " '" + f + "'";
  cmd += " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  r.report.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!WIFEXITED(status)) {
    r.status = -1;
  } else if (WEXITSTATUS(status) == 77) {
    r.skipped = r.report;
  } else {
    r.status = WEXITSTATUS(status);
  }
  return r;
}

}  // namespace rad::testing
