// The box tree: every item in exactly one leaf, boxes that hold their items, and a walk that
// prunes what its caller says and hands children their parent's value.
#include "core/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace rad {
namespace {

struct Items {
  std::vector<Aabb> boxes;
  std::vector<Vec3> centres;
};

Items random_items(size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> at(-10.0f, 10.0f), size(0.0f, 0.5f);
  Items it;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 c(at(rng), at(rng), at(rng)), h(size(rng), size(rng), size(rng));
    Aabb b;
    b.extend(c - h), b.extend(c + h);
    it.boxes.push_back(b), it.centres.push_back(c);
  }
  return it;
}

TEST(BoxTree, EveryItemIsInOneLeafWhoseAncestorsBoxesHoldIt) {
  const Items it = random_items(1000);
  const BoxTree t = make_box_tree(it.boxes, it.centres, 8);
  ASSERT_GT(t.size(), 1u);
  std::vector<int> seen(it.boxes.size(), 0);
  for (size_t n = 0; n < t.size(); ++n) {
    for (uint32_t k = t.first[n]; k < t.first[n] + t.count[n]; ++k) {
      const Aabb& b = it.boxes[t.order[k]];
      EXPECT_TRUE(glm::all(glm::lessThanEqual(t.box[n].lo, b.lo)) &&
                  glm::all(glm::greaterThanEqual(t.box[n].hi, b.hi)));
      if (t.leaf(n)) ++seen[t.order[k]];
    }
    if (t.leaf(n)) {
      EXPECT_LE(t.count[n], 8u);
    } else {
      EXPECT_EQ(t.count[n + 1] + t.count[t.right[n]], t.count[n]);
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  // The same items give the same tree.
  const BoxTree again = make_box_tree(it.boxes, it.centres, 8);
  EXPECT_EQ(again.order, t.order);
  EXPECT_EQ(again.right, t.right);
}

TEST(BoxTree, AWalkPrunesWhatItsCallerRefusesAndPassesValuesDown) {
  const Items it = random_items(500);
  const BoxTree t = make_box_tree(it.boxes, it.centres, 4);
  // Items whose centre has x < 0, found by pruning boxes wholly at x >= 0; each node's depth
  // passed down as the value.
  std::vector<std::pair<uint32_t, int>> stack;
  std::vector<uint32_t> found;
  int deepest = 0;
  walk_box_tree(
      t, 0, 0, stack,
      [&](uint32_t node, int& depth) {
        deepest = std::max(deepest, depth);
        ++depth;
        return t.box[node].lo.x < 0.0f;
      },
      [&](uint32_t node) {
        for (uint32_t k = t.first[node]; k < t.first[node] + t.count[node]; ++k)
          if (it.centres[t.order[k]].x < 0.0f) found.push_back(t.order[k]);
      });
  std::sort(found.begin(), found.end());
  std::vector<uint32_t> want;
  for (uint32_t i = 0; i < it.centres.size(); ++i)
    if (it.centres[i].x < 0.0f) want.push_back(i);
  EXPECT_EQ(found, want);
  EXPECT_GT(deepest, 4);
}

}  // namespace
}  // namespace rad
