#pragma once
// Integrals over the sphere of directions for the BRDF and BSDF tests (densities that must
// integrate to the share their sampler keeps, albedos).

#include <cmath>

#include <glm/vec3.hpp>

namespace igi::testing {

/// The integral of f(w) over the sphere, on a latitude-longitude grid about +z (fine near the
/// poles, where the lobes of a head-on view peak) of `steps` x 2 `steps` cells, each weighed by
/// its solid angle: enough for the densities of the tests to integrate within 1e-3.
template <typename F>
double integrateOverSphere(F&& f, int steps = 1024) {
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double theta = (i + 0.5) * M_PI / steps;
        const double ring = std::sin(theta) * (M_PI / steps) * (2.0 * M_PI / (2 * steps));
        for (int j = 0; j < 2 * steps; ++j) {
            const double phi = (j + 0.5) * 2.0 * M_PI / (2 * steps);
            const glm::vec3 w(float(std::sin(theta) * std::cos(phi)),
                              float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
            sum += f(w) * ring;
        }
    }
    return sum;
}

/// The unit direction in the xz plane at `cosTheta` from +z: a view of a surface facing +z.
inline glm::vec3 viewAt(float cosTheta) {
    return {std::sqrt(1 - cosTheta * cosTheta), 0.0f, cosTheta};
}

}  // namespace igi::testing
