#include "SurfaceBrdf.h"

#include "math/Frame.h"

namespace igi {

glm::vec3 SurfaceBrdf::sample(glm::vec2 u, float uLobe) const {
    if (uLobe < sampleDiffuse) return Frame(normal).toWorld(squareToCosineHemisphere(u));
    if (model == GlossyModel::Ggx) return ggx::sample(alpha, normal, wo, u);
    return Frame(mirror).toWorld(squareToPhongLobe(u, exponent));
}

}  // namespace igi
