// Every input kept under fuzz_regressions/READER (hostile inputs written by hand and every
// finding of tools/fuzz) goes through that reader's fuzz target (fuzz/READER_fuzz.cpp, linked
// in): it must end in a result or one rad::Error, under the sanitizers when the suite has them.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

// RAD_FUZZ_SUITE names the suite per reader (FuzzRegressionsOff, ...) so ctest names differ.
TEST(RAD_FUZZ_SUITE, EveryKeptInputEndsInAResultOrOneError) {
  const fs::path dir = fs::path(RAD_SOURCE_DIR) / "tests/scene/fuzz_regressions" / RAD_FUZZ_READER;
  int inputs = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), {}};
    SCOPED_TRACE(e.path().string());
    // The target swallows rad::Error only: anything else thrown fails here, a crash fails the
    // run, and the sanitizer builds fail on any report.
    EXPECT_NO_THROW(
        LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    ++inputs;
  }
  EXPECT_GE(inputs, 4) << dir;
}

}  // namespace
