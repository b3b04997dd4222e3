#include "core/box_tree.h"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace rad {

namespace {

uint32_t build_node(BoxTree& tree, std::span<const Aabb> boxes, std::span<const Vec3> centres,
                    uint32_t leaf_size, uint32_t first, uint32_t count) {
  const uint32_t node = uint32_t(tree.box.size());
  Aabb box, spread;
  for (uint32_t k = first; k < first + count; ++k) {
    const uint32_t i = tree.order[k];
    box.extend(boxes[i]);
    spread.extend(centres[i]);
  }
  tree.box.push_back(box);
  tree.first.push_back(first), tree.count.push_back(count), tree.right.push_back(0);
  if (count <= leaf_size) return node;
  const int axis = spread.widest_axis();
  const uint32_t half = count / 2;
  auto begin = tree.order.begin() + first;
  std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
    return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
  });
  build_node(tree, boxes, centres, leaf_size, first, half);
  const uint32_t right = build_node(tree, boxes, centres, leaf_size, first + half, count - half);
  tree.right[node] = right;
  return node;
}

}  // namespace

BoxTree make_box_tree(std::span<const Aabb> boxes, std::span<const Vec3> centres,
                      uint32_t leaf_size) {
  assert(boxes.size() == centres.size() && leaf_size >= 1);
  BoxTree tree;
  if (boxes.empty()) return tree;
  tree.order.resize(boxes.size());
  std::iota(tree.order.begin(), tree.order.end(), 0u);
  build_node(tree, boxes, centres, leaf_size, 0, uint32_t(boxes.size()));
  return tree;
}

}  // namespace rad
