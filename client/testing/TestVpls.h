#pragma once

#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "lights/Vpl.h"

namespace igi::testing {

/// What a room's VPLs may hold besides plain Lambertian ones.
struct RoomVplMix {
    bool fewBright = false;      ///< every seventh (from the first) 20 times brighter
    bool ggxEveryThird = false;  ///< every third (from the second) a GGX metal lobe
};

/// `count` VPLs scattered over a room's walls, floor and ceiling, some facing away from any
/// point, drawn from `random` (the same draws whatever `mix` asks, so a seed gives the same
/// positions, normals and powers).
inline std::vector<Vpl> roomVpls(int count, std::mt19937& random, RoomVplMix mix = {}) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Vpl> vpls;
    for (int i = 0; i < count; ++i) {
        Vpl v;
        v.position = {8 * u(random) - 4, 3 * u(random), 6 * u(random) - 3};
        v.normal = glm::normalize(glm::vec3(u(random) - 0.5f, u(random) - 0.5f, u(random) - 0.5f));
        v.power = glm::vec3(0.1f + u(random), 0.1f + u(random), 0.1f + u(random));
        if (mix.fewBright && i % 7 == 0) v.power *= 20.0f;
        if (mix.ggxEveryThird && i % 3 == 1) {
            v.ggx = true;
            v.exponent = 0.1f;
            v.f0 = glm::vec3(0.9f);
            v.glossyPower = v.power * 4.0f;
            v.mirror = v.normal;
            v.diffuseShare = 0.2f;
            v.glossyShare = 0.8f;
        }
        vpls.push_back(v);
    }
    return vpls;
}

}  // namespace igi::testing
