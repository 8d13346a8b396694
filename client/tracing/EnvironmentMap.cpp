#include "tracing/EnvironmentMap.h"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

#include "math/Color.h"
#include "math/Warp.h"

namespace igi {

EnvironmentMap::EnvironmentMap(const Environment& environment, const std::vector<Texture>& textures)
    : present_(environment.present()),
      factor_(environment.radiance),
      rotateDeg_(environment.rotateDeg) {
    if (!present_) return;
    if (environment.texture < 0 || std::size_t(environment.texture) >= textures.size()) {
        meanLuminance_ = luminance(factor_);
        return;
    }
    map_ = &textures[std::size_t(environment.texture)];
    const int w = map_->width, h = map_->height;
    std::vector<float> rowWeights(std::size_t(h), 0.0f), columnWeights(static_cast<std::size_t>(w));
    columns_.resize(std::size_t(h));
    double total = 0;
    for (int y = 0; y < h; ++y) {
        double row = 0;
        for (int x = 0; x < w; ++x) {
            columnWeights[std::size_t(x)] = std::max(0.0f, luminance(texel({x, y})));
            row += columnWeights[std::size_t(x)];
        }
        columns_[std::size_t(y)] = Distribution1D(columnWeights);
        const double weight = row * double(texelSolidAngle(y));
        rowWeights[std::size_t(y)] = float(weight);
        total += weight;
    }
    rows_ = Distribution1D(rowWeights);
    meanLuminance_ = float(total / (4.0 * double(kPi)));
    if (rows_.empty()) present_ = false;  // a black map lights nothing
}

float EnvironmentMap::texelSolidAngle(int row) const {
    const float h = float(map_->height);
    const float cos0 = std::cos(kPi * float(row) / h), cos1 = std::cos(kPi * float(row + 1) / h);
    return 2.0f * kPi / float(map_->width) * (cos0 - cos1);
}

glm::ivec2 EnvironmentMap::texelOf(glm::vec3 toSky) const {
    const glm::vec2 uv = equirectUv(turnAboutUp(toSky, -rotateDeg_));
    return {std::clamp(int(uv.x * float(map_->width)), 0, map_->width - 1),
            std::clamp(int(uv.y * float(map_->height)), 0, map_->height - 1)};
}

glm::vec3 EnvironmentMap::texel(glm::ivec2 t) const {
    return factor_ * map_->texels[std::size_t(t.y) * std::size_t(map_->width) + std::size_t(t.x)];
}

glm::vec3 EnvironmentMap::radiance(glm::vec3 toSky) const {
    if (!present_) return glm::vec3(0.0f);
    if (!map_) return factor_;
    return texel(texelOf(toSky));
}

EnvironmentMap::Sample EnvironmentMap::sample(glm::vec2 u) const {
    Sample s;
    if (!present_) return s;
    if (!map_) {
        s.toSky = squareToUniformSphere(u);
        s.radiance = factor_;
        s.pdf = 1.0f / (4.0f * kPi);
        return s;
    }
    float uRow = 0, uColumn = 0;
    const std::size_t row = rows_.sample(u.y, &uRow);
    const std::size_t column = columns_[row].sample(u.x, &uColumn);
    // Uniform in solid angle within the texel: uniform in the angle about the pole and in cos.
    const float h = float(map_->height);
    const float cos0 = std::cos(kPi * float(row) / h), cos1 = std::cos(kPi * float(row + 1) / h);
    const float cosTheta = cos0 + uRow * (cos1 - cos0);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = ((float(column) + uColumn) / float(map_->width) - 0.5f) * 2.0f * kPi;
    const glm::vec3 local(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
    s.toSky = turnAboutUp(local, rotateDeg_);
    s.radiance = texel({int(column), int(row)});
    s.pdf = rows_.pdf(row) * columns_[row].pdf(column) / texelSolidAngle(int(row));
    return s;
}

float EnvironmentMap::pdf(glm::vec3 toSky) const {
    if (!present_) return 0.0f;
    if (!map_) return 1.0f / (4.0f * kPi);
    const glm::ivec2 t = texelOf(toSky);
    const Distribution1D& columns = columns_[std::size_t(t.y)];
    if (columns.empty()) return 0.0f;
    return rows_.pdf(std::size_t(t.y)) * columns.pdf(std::size_t(t.x)) / texelSolidAngle(t.y);
}

}  // namespace igi
