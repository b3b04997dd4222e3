// Scenes made of quads, built in code for solver tests.
#pragma once

#include <memory>

#include "hierarchy/hierarchy.h"
#include "scene/description.h"
#include "scenegen/model_pairs.h"
#include "solver/solver.h"
#include "solver/solver_state.h"

namespace rad::testing {

/// A solved scene: the hierarchy, its backend and the solver state that points into both.
struct Solved {
  Hierarchy h;
  std::unique_ptr<VisibilityBackend> vis;
  SolverState s;
};

/// Appends a Pure made of a quad (model_pairs.h).
using rad::add_quad;

/// Axis-aligned box [lo, hi] with all six faces facing inwards, one Pure per face.
inline void add_closed_box(SceneDescription& s, Vec3 lo, Vec3 hi, Vec3 rho, Vec3 e, int k = 1) {
  const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                     {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                     {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  add_quad(s, "bottom", p[0], p[1], p[2], p[3], rho, e, k);  // z = lo, normal +z
  add_quad(s, "top", p[4], p[7], p[6], p[5], rho, e, k);     // z = hi, normal -z
  add_quad(s, "front", p[0], p[4], p[5], p[1], rho, e, k);   // y = lo, normal +y
  add_quad(s, "back", p[3], p[2], p[6], p[7], rho, e, k);    // y = hi, normal -y
  add_quad(s, "left", p[0], p[3], p[7], p[4], rho, e, k);    // x = lo, normal +x
  add_quad(s, "right", p[1], p[5], p[6], p[2], rho, e, k);   // x = hi, normal -x
}

/// A solve of `h` with options `o` stopped after `shots` shots (never by convergence).
inline SolverState solve_shots(const Hierarchy& h, const VisibilityBackend& vis, SolverOptions o,
                               int shots) {
  o.converge = 0.0;
  o.max_shots = shots;
  SolverState s = make_solver_state(h, o);
  solve(s, vis);
  return s;
}

}  // namespace rad::testing
