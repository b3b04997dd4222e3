// Test parameters naming every visibility backend configuration (kind × packets).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "visibility/backend.h"

namespace rad {

struct BackendParam {
  BackendKind kind;
  bool packets;
};

inline const auto kAllBackends = testing::Values(
    BackendParam{BackendKind::Embree, true}, BackendParam{BackendKind::Embree, false},
    BackendParam{BackendKind::Grid, true}, BackendParam{BackendKind::Brute, true});

inline std::string backend_param_name(const testing::TestParamInfo<BackendParam>& info) {
  std::string name = to_string(info.param.kind);
  if (info.param.kind == BackendKind::Embree) name += info.param.packets ? "_packets" : "_single";
  return name;
}

}  // namespace rad
