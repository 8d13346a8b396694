#include "materials/SurfaceBrdf.h"

#include "math/Frame.h"

namespace igi {

glm::vec3 SurfaceBrdf::sample(glm::vec2 u, float uLobe) const {
    if (model == GlossyModel::Ggx) {
        if (uLobe < 1.0f - glossySampling())
            return Frame(normal).toWorld(squareToCosineHemisphere(u));
        return ggx::sample(exponent, normal, view(), u);
    }
    if (uLobe < diffuseShare) return Frame(normal).toWorld(squareToCosineHemisphere(u));
    return Frame(mirror).toWorld(squareToPhongLobe(u, exponent));
}

}  // namespace igi
