#include "ImageSize.h"

#include <algorithm>
#include <cmath>

namespace igi {
namespace {

// `edge` scaled by given / sceneEdge, as a whole number of pixels within [1, maxEdge].
int scaled(int edge, int given, int sceneEdge, int maxEdge) {
    const double v = std::round(double(edge) * double(given) / double(std::max(1, sceneEdge)));
    return int(std::clamp(v, 1.0, double(maxEdge)));
}

}  // namespace

ImageSize overriddenImageSize(ImageSize scene, int width, int height, int maxEdge) {
    if (width > 0 && height > 0) return {width, height};
    if (width > 0) return {width, scaled(scene.height, width, scene.width, maxEdge)};
    if (height > 0) return {scaled(scene.width, height, scene.height, maxEdge), height};
    return scene;
}

}  // namespace igi
