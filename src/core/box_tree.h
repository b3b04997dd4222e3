// A bounding-volume tree that knows only boxes and their centres: median splits along the
// widest axis of the centres. Who walks it says what a node means to them.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/aabb.h"

namespace rad {

/// Node i holds items order[first[i] .. first[i] + count[i]) inside box[i]; an inner node's
/// children are i + 1 and right[i] (nodes in depth-first order).
struct BoxTree {
  std::vector<Aabb> box;
  std::vector<uint32_t> first, count, right;
  std::vector<uint32_t> order;
  bool leaf(size_t i) const { return right[i] == 0; }
  size_t size() const { return box.size(); }
};

/// The tree over items with boxes `boxes` and centres `centres` (same length): a node of more
/// than `leaf_size` items splits at the median of its centres along their widest axis, ties
/// broken by index, so the same items give the same tree.
BoxTree make_box_tree(std::span<const Aabb> boxes, std::span<const Vec3> centres,
                      uint32_t leaf_size);

/// Depth first from node `start`, each node with a value of the caller's (what may still be
/// said of it, e.g. which occluders may still hide it) that its children inherit:
/// `enter(node, value)` says whether to look inside (false prunes the node) and may change the
/// value for the children; a leaf entered is handed to `leaf(node)`. `stack` is the caller's,
/// reused: no allocation once it is big enough.
template <typename Value, typename Enter, typename Leaf>
void walk_box_tree(const BoxTree& tree, uint32_t start, Value value,
                   std::vector<std::pair<uint32_t, Value>>& stack, Enter&& enter, Leaf&& leaf) {
  stack.assign(1, {start, value});
  while (!stack.empty()) {
    auto [node, v] = stack.back();
    stack.pop_back();
    if (!enter(node, v)) continue;
    if (tree.leaf(node)) {
      leaf(node);
    } else {
      stack.push_back({tree.right[node], v});
      stack.push_back({node + 1, v});
    }
  }
}

}  // namespace rad
