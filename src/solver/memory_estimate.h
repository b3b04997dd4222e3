// What a solve may cost in memory, known before the first shot: the mesh can only grow by
// subdivision, and subdivision stops at the smallest element edge (--min-size).
#pragma once

#include "solver/solver_state.h"

namespace rad {

/// Bytes the mesh would grow by if every leaf were split as far as min_size allows (a split
/// needs a size L >= 2 min_size, L its split_size with every edge (mesh/subdivide.h), so a
/// leaf splits d = floor(log2(L / (2 min_size))) + 1 levels deep): vertex tables,
/// elements and midpoint maps, with the slack of growing vectors. An upper bound but for the
/// splits below min_size at the edges of covers; real solves split where the light changes, a
/// small part.
double worst_case_growth_bytes(const SolverState& s);

/// Bytes one logged shot of cluster c keeps (its samples and fine samples; solver_state.h).
double shot_log_bytes(const SolverState& s, size_t c);

}  // namespace rad
