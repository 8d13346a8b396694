#include "tracing/AlphaCoverage.h"

#include <bit>

#include "sampling/Hash.h"

namespace igi {

bool hasCutOuts(const Material& m, const std::vector<Texture>& textures) {
    if (m.alphaMode == AlphaMode::Opaque) return false;
    float least = m.alpha;
    if (m.alphaTexture >= 0 && m.alphaTexture < static_cast<int>(textures.size()))
        least *= textures[m.alphaTexture].alphaMinimum;
    return m.alphaMode == AlphaMode::Mask ? !(least >= m.alphaCutoff) : least < 1.0f;
}

float alphaAt(const Material& m, const std::vector<Texture>& textures, glm::vec2 uv) {
    float a = m.alpha;
    if (m.alphaTexture >= 0 && m.alphaTexture < static_cast<int>(textures.size()))
        a *= textures[m.alphaTexture].sampleAlpha(m.alphaUv(uv));
    return a;
}

float coverageRandom(glm::vec3 origin, glm::vec3 direction, std::uint32_t mesh,
                     std::uint32_t triangle) {
    auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
    const std::uint64_t h =
        hashValues(0x616c706861ull,  // "alpha": a stream of its own
                   bits(origin.x), bits(origin.y), bits(origin.z), bits(direction.x),
                   bits(direction.y), bits(direction.z), mesh, triangle);
    return static_cast<float>(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, below 1
}

bool covers(const Material& m, float alpha, float random) {
    switch (m.alphaMode) {
        case AlphaMode::Mask:
            return alpha >= m.alphaCutoff;
        case AlphaMode::Blend:
            return random < alpha;
        default:
            return true;
    }
}

bool CutOutTriangles::hits(glm::vec3 origin, glm::vec3 direction, std::uint32_t prim, float u,
                           float v) const {
    const std::uint32_t t = triangles[prim];
    const Material& m =
        (*materials)[material >= 0 ? std::uint32_t(material) : mesh->materialIds[t]];
    // The uv of the hit as TraceableScene::fillSurfacePoint computes it.
    glm::vec2 uv(u, v);
    if (!mesh->uvs.empty()) {
        const glm::uvec3 tri = mesh->triangles[t];
        const float w = 1.0f - u - v;
        uv = w * mesh->uvs[tri.x] + u * mesh->uvs[tri.y] + v * mesh->uvs[tri.z];
    }
    const float alpha = alphaAt(m, *textures, uv);
    const float random =
        m.alphaMode == AlphaMode::Blend ? coverageRandom(origin, direction, meshIndex, t) : 0.0f;
    return covers(m, alpha, random);
}

void coverageFilter(const RTCFilterFunctionNArguments* args) {
    const auto* cutOut = static_cast<const CutOutTriangles*>(args->geometryUserPtr);
    const unsigned n = args->N;
    RTCRayN* ray = args->ray;
    RTCHitN* hit = args->hit;
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::vec3 origin(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i),
                               RTCRayN_org_z(ray, n, i));
        const glm::vec3 direction(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i),
                                  RTCRayN_dir_z(ray, n, i));
        if (!cutOut->hits(origin, direction, RTCHitN_primID(hit, n, i), RTCHitN_u(hit, n, i),
                          RTCHitN_v(hit, n, i)))
            args->valid[i] = 0;
    }
}

}  // namespace igi
