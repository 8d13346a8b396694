#pragma once

#include <glm/vec3.hpp>

#include "lights/VplChoice.h"
#include "materials/SurfaceBrdf.h"
#include "math/Lanes.h"

namespace igi {

/// The first half of VplChoice::choose: each VPL's importance w_i at the point at `origin`
/// (shading normal n, geometric normal f; `dmin2` the set's bound distance squared), ranked by
/// the GGX lobes as VplChoice.h describes where `ggxReceiver` (then `receiver` is that BRDF) or
/// a VPL's lobe asks for it, and the running sums of the w and of the reachable VPLs (1 each)
/// up to each VPL, written to `weight`, `sumW` and `sumR` (each of choice.lum.size() floats).
///
/// Eight VPLs at a time where the processor has AVX2 (lanes::bestIsa()), else four; the sums
/// run four lanes at a time in either, in one fixed order, so both give the same bits (the
/// choice of a pixel must not depend on the client's processor).
void vplWeights(const VplChoice& choice, glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2,
                bool ggxReceiver, const SurfaceBrdf* receiver, float* weight, float* sumW,
                float* sumR, lanes::Isa isa = lanes::bestIsa());

}  // namespace igi
