// The solver's state on disk, so a long run killed at any point resumes where it last saved and
// ends byte-identical to a run never stopped (the solver is deterministic).
#pragma once

#include <cstdint>
#include <string>

#include "solver/solver_state.h"

namespace rad {

/// Identity of a solve: the hierarchy (triangles, objects, materials), every solver option that
/// changes the answer (not the stop criteria: a resumed run may go further), the visibility
/// backend and the checkpoint format. A checkpoint resumes only a solve with the same identity.
uint64_t solve_fingerprint(const Hierarchy& h, const SolverOptions& o, BackendKind backend);

/// Writes everything the state holds beyond what make_solver_state rebuilds (the mesh and its
/// radiosity, materials, energies, the shot log, counters and history), with `fingerprint` and a
/// checksum, durably and atomically: a kill at any time leaves the previous checkpoint or this.
/// Throws rad::Error when it cannot.
void write_checkpoint(const std::string& path, const SolverState& s, uint64_t fingerprint);

/// Restores into `s` (fresh from make_solver_state for the same solve) the state written to
/// `path`. Throws rad::Error naming the file when it is not a checkpoint, is corrupt or
/// truncated, or was written for a solve of another fingerprint; `s` is untouched then.
void read_checkpoint(const std::string& path, SolverState& s, uint64_t fingerprint);

}  // namespace rad
