#include "SurfaceBrdf.h"

#include "math/Frame.h"

namespace igi {

glm::vec3 SurfaceBrdf::sample(glm::vec2 u, float uLobe, glm::vec3 mirror) const {
    if (uLobe < diffuseShare) return Frame(normal).toWorld(squareToCosineHemisphere(u));
    return Frame(mirror).toWorld(squareToPhongLobe(u, exponent));
}

}  // namespace igi
