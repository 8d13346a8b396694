#include "lights/VplChoice.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lights/VplWeights.h"
#include "math/Color.h"
#include "math/Float4.h"

namespace igi {

void VplChoice::prepare(const std::vector<Vpl>& vpls, std::uint32_t points, float u) {
    perPoint = points;
    offset = u;
    // The choice reads four lanes at a time, the Lambertian links (LambertianLinks) up to
    // eight: positions, normals and glossy bits go on to a multiple of eight.
    const std::size_t padded = (vpls.size() + 3) / 4 * 4, wide = (vpls.size() + 7) / 8 * 8;
    for (auto* v : {&px, &py, &pz, &nx, &ny, &nz}) v->assign(wide, 0.0f);
    lum.assign(padded, 0.0f);
    general.assign(wide / 4, 0);
    anyGeneral = false;
    ggxBits.assign(padded / 4, 0);
    ggxSlot.assign(padded, 0);
    ggxVpls.clear();
    for (std::size_t i = 0; i < vpls.size(); ++i) {
        const Vpl& v = vpls[i];
        px[i] = v.position.x, py[i] = v.position.y, pz[i] = v.position.z;
        // A VPL on a mapped surface bends its normal toward each receiver (Vpl::bends): its
        // lane holds the geometric normal, on whose side it can light a point at all.
        const glm::vec3 normal = v.bends ? v.face : v.normal;
        nx[i] = normal.x, ny[i] = normal.y, nz[i] = normal.z;
        lum[i] = std::max(0.0f, luminance(v.power) + luminance(v.glossyPower));
        if (v.glossy() || v.omni || v.bends) {
            general[i / 4] |= std::uint8_t(1u << (i % 4));
            anyGeneral = true;
        }
        if (v.glossy() && v.ggx) {
            ggxBits[i / 4] |= std::uint8_t(1u << (i % 4));
            ggxSlot[i] = std::uint32_t(ggxVpls.size());
            ggxVpls.push_back(v);
        }
    }
}

std::uint32_t VplChoice::choose(glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2, Pick* out,
                                const SurfaceBrdf* receiver) const {
    // A GGX receiver weighs every VPL by its lobe; Lambertian and Phong receivers keep the
    // Lambertian importance (and its bits: scenes without GGX choose exactly as before).
    const bool ggxReceiver =
        receiver != nullptr && receiver->model == GlossyModel::Ggx && receiver->hasGlossy();
    const std::size_t padded = lum.size();
    // Per VPL: its importance w_i, and the running sums of the w and of the reachable VPLs
    // up to it (so that the CDF needs no second walk in sequence).
    thread_local std::vector<float> weights, sumsW, sumsR;
    weights.resize(padded), sumsW.resize(padded), sumsR.resize(padded);
    // Their memory by plain pointers: the loops then address it without looking up the
    // thread's storage again at every store.
    float* const weight = weights.data();
    float* const sumW = sumsW.data();
    float* const sumR = sumsR.data();
    vplWeights(*this, origin, n, f, dmin2, ggxReceiver, receiver, weight, sumW, sumR);
    const float sum = sumW[padded - 1], reachable = sumR[padded - 1];
    if (!(sum > 0) || !(reachable > 0) || !std::isfinite(sum)) return 0;
    // p_i = (1 - s) w_i / sum + s / reachable for the reachable VPLs, 0 for the others, so the
    // CDF at VPL i is a sumW_i + b sumR_i. Sample j sits at (j + offset) / N: those below a CDF
    // value c are the j < N c - offset, ceil(N c - offset) of them (clamped to [0, N]), and
    // VPL i takes those below its CDF less those below the previous VPL's. Four VPLs at a time,
    // no branch on the data but where a VPL took samples.
    const float a = (1.0f - kUniformShare) / sum, b = kUniformShare / reachable;
    const float draws = float(perPoint);
    const Float4 a4(a), b4(b), draws4(draws), offset4(offset), zero(0.0f);
    std::uint32_t picked = 0;
    float below = 0;  // samples below the previous VPL's CDF
    for (std::size_t i = 0; i < padded && below < draws; i += 4) {
        const Float4 cdf = a4 * Float4::load(&sumW[i]) + b4 * Float4::load(&sumR[i]);
        const Float4 raw = ceilNonNegative(min(max(draws4 * cdf - offset4, zero), draws4));
        // The running sums rise lane by lane but the fourth, summed as (w0 + w1) + (w2 + w3),
        // may round an ulp below the third's w0 + (w1 + w2): the counts must not fall (a fall
        // would hand a sample out twice).
        const Float4 upTo = max(raw, shiftIn(raw, below));
        const Float4 times = upTo - shiftIn(upTo, below);
        const unsigned took = laneBits(greater(times, zero));
        if (took) {
            // The scales of the four lanes in one division (each lane as the scalar
            // times / (draws (a w_i + b))), the taken ones written out.
            float scale[4];
            (times / (draws4 * (a4 * Float4::load(&weight[i]) + b4))).store(scale);
            for (unsigned bits = took; bits; bits &= bits - 1) {
                const int k = __builtin_ctz(bits);
                out[picked++] = {std::uint32_t(i + k), scale[k]};
            }
        }
        below = lastLaneValue(upTo);
    }
    // The CDF may end a rounding error short of 1: the last reachable VPL takes what is left.
    if (below < draws) {
        std::size_t last = padded;
        while (last > 0 && !(weight[last - 1] > 0)) --last;
        if (last-- == 0) return 0;  // cannot happen: some VPL is reachable
        const float p = a * weight[last] + b;
        float times = draws - below;
        if (picked > 0 && out[picked - 1].index == last) times += out[--picked].scale * draws * p;
        out[picked++] = {std::uint32_t(last), std::round(times) / (draws * p)};
    }
    return picked;
}

}  // namespace igi
