// The FNV-1a hash behind checkpoint fingerprints and checksums.
#include "core/fingerprint.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

TEST(Fingerprint, MatchesTheFnv1aReferenceValues) {
  // Published FNV-1a 64 test vectors.
  EXPECT_EQ(Fingerprint().value(), 0xcbf29ce484222325ull);
  EXPECT_EQ(Fingerprint().bytes("a", 1).value(), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(Fingerprint().bytes("foobar", 6).value(), 0x85944171f73967e8ull);
}

TEST(Fingerprint, StringsAreLengthPrefixedSoSplitsDiffer) {
  EXPECT_NE(Fingerprint().add("ab").add("c").value(), Fingerprint().add("a").add("bc").value());
  EXPECT_EQ(Fingerprint().add(1.5f).add(int32_t(2)).value(),
            Fingerprint().add(1.5f).add(int32_t(2)).value());
  EXPECT_NE(Fingerprint().add(1.5f).value(), Fingerprint().add(-1.5f).value());
}

}  // namespace
}  // namespace rad
