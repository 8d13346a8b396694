#pragma once

#include "MasterOptions.h"
#include "scene/Scene.h"

namespace igi {

/// Says how the scene is lit when that is not by its own lights (a headlight, and why), and
/// warns when nothing lights it: a black image must not come as a surprise.
void reportLighting(const Scene& scene, const MasterOptions& options);

}  // namespace igi
