// A small scene for the serve tests: a closed box with a lamp, grouped as an Assembly holding
// a Composite, so requests can name objects of every kind.
#pragma once

#include <string>

#include "../solver/scene_builder.h"
#include "hierarchy/hierarchy.h"
#include "solver/options.h"

namespace rad::testing {

inline const Vec3 kLampEmission(5.0f);

inline SceneDescription serve_scene(Vec3 lamp_emission = kLampEmission) {
  SceneDescription d;
  d.name = "serve test box";
  const Vec3 w(0.6f, 0.55f, 0.5f), red(0.6f, 0.1f, 0.1f);
  add_closed_box(d, Vec3(0.0f), Vec3(1.0f), w, Vec3(0.0f));
  d.objects[4].material.reflectance = red;  // "left"
  add_quad(d, "lamp", {0.4f, 0.4f, 0.99f}, {0.4f, 0.6f, 0.99f}, {0.6f, 0.6f, 0.99f},
           {0.6f, 0.4f, 0.99f}, Vec3(0.5f), lamp_emission);
  // room (Assembly) { walls (Composite) { six faces }, lamp }
  ObjectDescription walls;
  walls.name = "walls";
  walls.kind = ObjectKind::Composite;
  for (int32_t i = 0; i < 6; ++i) walls.children.push_back(i);
  ObjectDescription room;
  room.name = "room";
  room.kind = ObjectKind::Assembly;
  room.children = {int32_t(d.objects.size()), 6};
  d.objects.push_back(walls);
  d.objects.push_back(room);
  d.roots = {int32_t(d.objects.size()) - 1};
  return d;
}

inline SolverOptions serve_options() {
  SolverOptions o;
  o.converge = 2e-4;
  o.subdivision_threshold = 0.1f;
  return o;
}

inline int32_t object_named(const Hierarchy& h, const std::string& name) {
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].name == name) return int32_t(i);
  }
  return -1;
}

}  // namespace rad::testing
