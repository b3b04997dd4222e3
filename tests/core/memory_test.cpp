// Memory figures of the process and the machine, and sizes as users write them.
#include "core/memory.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/error.h"

namespace rad {
namespace {

TEST(Memory, ResidentGrowsWithWhatTheProcessTouchesAndStaysBelowTheMachine) {
  const size_t before = resident_bytes();
  std::vector<char> block(64 << 20, 1);  // 64 MiB, every page written
  const size_t after = resident_bytes();
  EXPECT_GT(before, 0u);
  EXPECT_GE(after, before + (48u << 20)) << "64 MiB touched";
  EXPECT_GT(machine_memory_bytes(), after);
  EXPECT_EQ(block[12345], 1);
}

TEST(Memory, ParsesSizesWithBinaryUnits) {
  EXPECT_EQ(parse_byte_size("2000000"), 2000000u);
  EXPECT_EQ(parse_byte_size("512M"), 512u << 20);
  EXPECT_EQ(parse_byte_size("8G"), size_t(8) << 30);
  EXPECT_EQ(parse_byte_size("8GB"), size_t(8) << 30);
  EXPECT_EQ(parse_byte_size("1.5GiB"), size_t(3) << 29);
  EXPECT_EQ(parse_byte_size("4k"), 4096u);
  EXPECT_EQ(parse_byte_size("1T"), size_t(1) << 40);
  for (const char* bad : {"", "G", "-1G", "0", "12Q", "1.5 GiB", "nan", "inf", "1e30", "3GiBs"}) {
    EXPECT_THROW(parse_byte_size(bad), Error) << bad;
  }
}

TEST(Memory, FormatsSizesForMessages) {
  EXPECT_EQ(format_bytes(512.0 * 1024), "512 KiB");
  EXPECT_EQ(format_bytes(300.0 * 1024 * 1024), "300 MiB");
  EXPECT_EQ(format_bytes(1.5 * 1024 * 1024 * 1024), "1.5 GiB");
}

}  // namespace
}  // namespace rad
