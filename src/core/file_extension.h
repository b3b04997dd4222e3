// A path's extension in lower case ("scene.GLB" -> ".glb"): how rad picks a file's format.
#pragma once

#include <string>

namespace rad {

std::string lower_extension(const std::string& path);

}  // namespace rad
