#include "tracing/EnvironmentMap.h"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

#include "math/Color.h"
#include "math/Warp.h"

namespace igi {

namespace {

// Whether `to` is k times `from` (k > 0) in every channel, to float precision.
bool proportional(glm::vec3 from, glm::vec3 to, float& k) {
    const int i = from.x >= from.y && from.x >= from.z ? 0 : from.y >= from.z ? 1 : 2;
    if (!(from[i] > 0.0f)) return false;
    k = to[i] / from[i];
    if (!(k > 0.0f)) return false;
    const float tolerance = 1e-6f * std::max({to.x, to.y, to.z});
    for (int c = 0; c < 3; ++c)
        if (std::abs(to[c] - k * from[c]) > tolerance) return false;
    return true;
}

}  // namespace

EnvironmentMap::EnvironmentMap(const Environment& environment, const std::vector<Texture>& textures)
    : environment_(environment),
      present_(environment.present()),
      factor_(environment.radiance),
      rotateDeg_(environment.rotateDeg) {
    if (!present_) return;
    if (environment.texture < 0 || std::size_t(environment.texture) >= textures.size()) {
        meanLuminance_ = luminance(factor_);
        return;
    }
    map_ = &textures[std::size_t(environment.texture)];
    auto tables = std::make_shared<Tables>();
    tables->factor = factor_;
    const int w = map_->width, h = map_->height;
    std::vector<float> rowWeights(std::size_t(h), 0.0f), columnWeights(static_cast<std::size_t>(w));
    tables->columns.resize(std::size_t(h));
    double total = 0;
    for (int y = 0; y < h; ++y) {
        double row = 0;
        for (int x = 0; x < w; ++x) {
            columnWeights[std::size_t(x)] = std::max(0.0f, luminance(texel({x, y})));
            row += columnWeights[std::size_t(x)];
        }
        tables->columns[std::size_t(y)] = Distribution1D(columnWeights);
        const double weight = row * double(texelSolidAngle(y));
        rowWeights[std::size_t(y)] = float(weight);
        total += weight;
    }
    tables->rows = Distribution1D(rowWeights);
    meanLuminance_ = float(total / (4.0 * double(kPi)));
    tables->meanLuminance = meanLuminance_;
    if (tables->rows.empty()) present_ = false;  // a black map lights nothing
    tables_ = std::move(tables);
}

EnvironmentMap EnvironmentMap::changedTo(const Environment& changed,
                                         const std::vector<Texture>& textures) const {
    if (changed == environment_) return *this;
    float k = 0;
    if (!tables_ || tables_->rows.empty() || changed.texture != environment_.texture ||
        !proportional(tables_->factor, changed.radiance, k))
        return EnvironmentMap(changed, textures);
    EnvironmentMap m = *this;
    m.environment_ = changed;
    m.present_ = true;
    m.factor_ = changed.radiance;
    m.rotateDeg_ = changed.rotateDeg;
    m.meanLuminance_ = tables_->meanLuminance * k;
    return m;
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
    return factor_ * map_->texel(t.x, t.y);
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
    const std::size_t row = tables_->rows.sample(u.y, &uRow);
    const std::size_t column = tables_->columns[row].sample(u.x, &uColumn);
    // Uniform in solid angle within the texel: uniform in the angle about the pole and in cos.
    const float h = float(map_->height);
    const float cos0 = std::cos(kPi * float(row) / h), cos1 = std::cos(kPi * float(row + 1) / h);
    const float cosTheta = cos0 + uRow * (cos1 - cos0);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = ((float(column) + uColumn) / float(map_->width) - 0.5f) * 2.0f * kPi;
    const glm::vec3 local(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
    s.toSky = turnAboutUp(local, rotateDeg_);
    s.radiance = texel({int(column), int(row)});
    s.pdf = tables_->rows.pdf(row) * tables_->columns[row].pdf(column) / texelSolidAngle(int(row));
    return s;
}

float EnvironmentMap::pdf(glm::vec3 toSky) const {
    if (!present_) return 0.0f;
    if (!map_) return 1.0f / (4.0f * kPi);
    const glm::ivec2 t = texelOf(toSky);
    const Distribution1D& columns = tables_->columns[std::size_t(t.y)];
    if (columns.empty()) return 0.0f;
    return tables_->rows.pdf(std::size_t(t.y)) * columns.pdf(std::size_t(t.x)) /
           texelSolidAngle(t.y);
}

}  // namespace igi
