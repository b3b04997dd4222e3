// Which part of the scene this process receives for, when ranks solve it together under MPI.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/ranks.h"

namespace rad {

/// Under MPI (distribute.h): the ranks solving together, the owner of each cluster and which
/// polygons are this rank's. One process: null and empty, every polygon its own.
struct Ownership {
  Ranks* ranks = nullptr;
  std::vector<uint32_t> cluster_owner;
  std::vector<uint8_t> owned;

  bool owns(size_t polygon) const { return owned.empty() || owned[polygon]; }
  bool owns_cluster(size_t c) const {
    return cluster_owner.empty() || cluster_owner[c] == uint32_t(ranks->rank());
  }
};

}  // namespace rad
