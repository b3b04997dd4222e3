// The camera a staged model (--stage, scene/stage.h) is seen through unless --camera gives one:
// the model, not its floor and light, framed from the stage's view direction.
#pragma once

#include "export/camera.h"
#include "scene/stage.h"

namespace rad {

/// Looks at the centre of the stage's model box from its view direction, with the default
/// field of view, from as near as keeps all eight corners of the box within the middle 85% of
/// an image of aspect `width / height`. Up is +y.
Camera stage_camera(const Stage& stage, float aspect);

}  // namespace rad
