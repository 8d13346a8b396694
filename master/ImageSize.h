#pragma once

namespace igi {

struct ImageSize {
    int width = 0;
    int height = 0;
};

/// The image size a run renders: the scene's, with --width and --height (0: not given) in
/// place of its own. Given only one of them, the other keeps the scene's aspect ratio (160
/// wide of a 640 x 480 scene is 160 x 120, not 160 x 480), rounded, at least 1 and at most
/// `maxEdge`.
ImageSize overriddenImageSize(ImageSize scene, int width, int height, int maxEdge = 16384);

}  // namespace igi
