// The replaced operator new (src/core/huge_pages.cpp), linked into this test as into rad: big
// blocks come on transparent huge pages where the kernel offers them, and every size still
// allocates, frees and fails as the standard says.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kReplaced = false;  // the sanitizers' operator new stands (huge_pages.cpp)
#else
constexpr bool kReplaced = true;
#endif

// The mapping holding `p` in /proc/self/smaps: its VmFlags ("hg": asked for huge pages) and its
// AnonHugePages in kB (-1: no mapping holds p).
struct Mapping {
  std::string flags;
  long huge_kb = -1;
};
Mapping mapping_at(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto at = reinterpret_cast<unsigned long>(p);
  bool inside = false;
  Mapping m;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      if (inside) break;
      inside = lo <= at && at < hi;
    } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
      m.huge_kb = std::stol(line.substr(14));
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      m.flags = line.substr(8) + " ";
    }
  }
  return m;
}

bool kernel_offers_huge_pages() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string s;
  std::getline(f, s);
  return s.find("[always]") != std::string::npos || s.find("[madvise]") != std::string::npos;
}

TEST(HugePages, ABigBlockIsAdvisedForHugePagesWhereTheKernelOffersThem) {
  if (!kReplaced) GTEST_SKIP() << "the sanitizers' operator new";
  if (!kernel_offers_huge_pages()) GTEST_SKIP() << "transparent huge pages are off";
  std::vector<char> block(size_t(64) << 20, 1);  // every page written (64 MiB: advised)
  const Mapping m = mapping_at(block.data() + block.size() / 2);
  ASSERT_GE(m.huge_kb, 0) << "no mapping holds the block";
  EXPECT_NE(m.flags.find(" hg "), std::string::npos) << "not advised: VmFlags" << m.flags;
  // Whether the kernel had huge pages free at the moment is up to the machine.
  if (m.huge_kb == 0) GTEST_SKIP() << "advised, but no huge page was free";
}

TEST(HugePages, ABlockBelowTheBoundIsLeftAlone) {
  if (!kReplaced) GTEST_SKIP() << "the sanitizers' operator new";
  // 16 MiB: mapped by glibc on its own while its threshold is low, from the heap once a big
  // free has raised it; advised in neither case.
  std::vector<char> block(size_t(16) << 20, 1);
  EXPECT_EQ(mapping_at(block.data() + block.size() / 2).flags.find(" hg "), std::string::npos);
}

TEST(HugePages, EverySizeAllocatesAndFreesAndTooMuchThrows) {
  for (size_t n : {size_t(0), size_t(1), size_t(4096), size_t(8) << 20, (size_t(8) << 20) + 1}) {
    std::unique_ptr<char[]> p(new char[n + 1]);
    p[n] = 7;
    EXPECT_EQ(p[n], 7);
    void* q = ::operator new(n);
    ::operator delete(q, n);
  }
  if (!kReplaced) return;  // the sanitizers abort on an impossible size unless told not to
  EXPECT_THROW((void)::operator new(size_t(1) << 62), std::bad_alloc);
  EXPECT_EQ(::operator new(size_t(1) << 62, std::nothrow), nullptr);
}

}  // namespace
