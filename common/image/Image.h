#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// A linear RGB float image, row-major, row 0 at the top.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h, glm::vec3(0.0f)) {}
    glm::vec3& at(int x, int y) { return pixels[std::size_t(y) * width + x]; }
    const glm::vec3& at(int x, int y) const { return pixels[std::size_t(y) * width + x]; }
};

}  // namespace igi
