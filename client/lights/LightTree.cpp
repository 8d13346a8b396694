#include "lights/LightTree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "math/Float4.h"

namespace igi {
namespace {

constexpr float kPiF = 3.14159265358979f;
constexpr float kOneBelow = 0x1.fffffep-1f;
// Bounds that rounding made a hair too tight would give a light that reaches the point an
// importance of zero, a bias: every cone is widened by this much (radians).
constexpr float kConeSlack = 1e-3f;
// Squared distances below this are taken as this: a receiver on a point light must not divide
// by zero (metres squared; scenes far smaller than a micrometre are not supported anyway).
constexpr float kMinDistance2 = 1e-12f;

struct Cone {
    glm::vec3 axis{0.0f, 0.0f, 1.0f};
    float cosSpread = 1;  ///< -1: every direction
};

float angleOf(float cosine) {
    return std::acos(std::clamp(cosine, -1.0f, 1.0f));
}

glm::vec3 rotate(glm::vec3 v, glm::vec3 unitAxis, float angle) {  // Rodrigues
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(unitAxis, v) * s + unitAxis * (glm::dot(unitAxis, v) * (1 - c));
}

// The smallest cone (of those this construction finds) holding both (pbrt-v4's Union).
Cone unite(const Cone& a, const Cone& b) {
    const Cone sphere{a.axis, -1.0f};
    if (a.cosSpread <= -1 || b.cosSpread <= -1) return sphere;
    const float ta = angleOf(a.cosSpread), tb = angleOf(b.cosSpread);
    const float td = angleOf(glm::dot(a.axis, b.axis));
    if (std::min(td + tb, kPiF) <= ta) return a;
    if (std::min(td + ta, kPiF) <= tb) return b;
    const float spread = 0.5f * (ta + td + tb) + kConeSlack;
    if (spread >= kPiF) return sphere;
    const glm::vec3 k = glm::cross(a.axis, b.axis);
    const float len = glm::length(k);
    if (!(len > 1e-12f)) return sphere;
    return {glm::normalize(rotate(a.axis, k / len, spread - kConeSlack - ta)), std::cos(spread)};
}

// A quarter of the box's squared diagonal: the squared radius of its bounding sphere.
float radius2Of(glm::vec3 lo, glm::vec3 hi) {
    const float gx = hi.x - lo.x, gy = hi.y - lo.y, gz = hi.z - lo.z;
    return 0.25f * (gx * gx + gy * gy + gz * gz);
}

float sinFromCos(float c) {
    return std::sqrt(std::max(0.0f, 1.0f - c * c));
}

}  // namespace

LightTree::LightTree(const std::vector<Light>& lights) {
    if (lights.empty()) return;
    std::vector<std::uint32_t> order(lights.size());
    std::iota(order.begin(), order.end(), 0u);
    std::vector<Binary> tree;
    tree.reserve(2 * lights.size());
    buildBinary(tree, order, 0, order.size(), lights);
    leafNode_.assign(lights.size(), 0);
    leafSlot_.assign(lights.size(), 0);
    nodes_.reserve(lights.size());
    collapse(tree, 0, 0, 0);
}

std::uint32_t LightTree::buildBinary(std::vector<Binary>& tree, std::vector<std::uint32_t>& order,
                                     std::size_t begin, std::size_t end,
                                     const std::vector<Light>& lights) {
    const auto index = std::uint32_t(tree.size());
    tree.emplace_back();
    if (end - begin == 1) {
        const Light& l = lights[order[begin]];
        Binary& leaf = tree[index];
        leaf.lo = l.lo;
        leaf.hi = l.hi;
        leaf.axis = l.omni ? glm::vec3(0.0f, 0.0f, 1.0f) : l.normal;
        leaf.cosSpread = l.omni ? -1.0f : std::cos(kConeSlack);
        leaf.power = std::max(0.0f, l.power);
        leaf.light = order[begin];
        return index;
    }
    // Split at the median of the centres along their widest extent.
    glm::vec3 cLo(INFINITY), cHi(-INFINITY);
    for (std::size_t i = begin; i < end; ++i) {
        const glm::vec3 c = 0.5f * (lights[order[i]].lo + lights[order[i]].hi);
        cLo = glm::min(cLo, c);
        cHi = glm::max(cHi, c);
    }
    const glm::vec3 extent = cHi - cLo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(middle),
                     order.begin() + std::ptrdiff_t(end), [&](std::uint32_t a, std::uint32_t b) {
                         const float ca = lights[a].lo[axis] + lights[a].hi[axis];
                         const float cb = lights[b].lo[axis] + lights[b].hi[axis];
                         return ca < cb || (ca == cb && a < b);
                     });
    buildBinary(tree, order, begin, middle, lights);
    const std::uint32_t second = buildBinary(tree, order, middle, end, lights);
    const Binary& a = tree[index + 1];
    const Binary& b = tree[second];
    const Cone cone = a.power <= 0   ? Cone{b.axis, b.cosSpread}
                      : b.power <= 0 ? Cone{a.axis, a.cosSpread}
                                     : unite({a.axis, a.cosSpread}, {b.axis, b.cosSpread});
    Binary& node = tree[index];
    node.lo = glm::min(a.lo, b.lo);
    node.hi = glm::max(a.hi, b.hi);
    node.axis = cone.axis;
    node.cosSpread = cone.cosSpread;
    node.power = a.power + b.power;
    node.second = second;
    return index;
}

std::uint32_t LightTree::collapse(const std::vector<Binary>& tree, std::uint32_t binary,
                                  std::uint32_t parent, std::uint32_t slot) {
    // The children: a leaf root alone; else each child, or its two children if it has them.
    std::vector<std::uint32_t> children;
    const Binary& b = tree[binary];
    if (b.second == 0) {
        children = {binary};
    } else {
        for (std::uint32_t c : {binary + 1, b.second}) {
            if (tree[c].second == 0) {
                children.push_back(c);
            } else {
                children.push_back(c + 1);
                children.push_back(tree[c].second);
            }
        }
    }
    const auto index = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    {
        Node& node = nodes_[index];
        node.parent = parent;
        node.slot = slot;
        for (int i = 0; i < 4; ++i) {  // unused lanes: no power, never chosen
            node.centreX[i] = node.centreY[i] = node.centreZ[i] = node.radius2[i] = 0;
            node.axisX[i] = node.axisY[i] = 0;
            node.axisZ[i] = 1;
            node.cosSpread[i] = -1;
            node.sinSpread[i] = 0;
            node.power[i] = 0;
            node.child[i] = 0;
        }
    }
    for (std::size_t i = 0; i < children.size(); ++i) {
        const Binary& c = tree[children[i]];
        std::uint32_t child = 0;
        if (c.second == 0) {
            child = c.light;
            leafNode_[c.light] = index;
            leafSlot_[c.light] = std::uint32_t(i);
        } else {
            child = collapse(tree, children[i], index, std::uint32_t(i));
        }
        Node& node = nodes_[index];  // collapse() may have moved the nodes
        node.centreX[i] = 0.5f * (c.lo.x + c.hi.x);
        node.centreY[i] = 0.5f * (c.lo.y + c.hi.y);
        node.centreZ[i] = 0.5f * (c.lo.z + c.hi.z);
        node.radius2[i] = radius2Of(c.lo, c.hi);
        node.axisX[i] = c.axis.x, node.axisY[i] = c.axis.y, node.axisZ[i] = c.axis.z;
        node.cosSpread[i] = c.cosSpread;
        node.sinSpread[i] = sinFromCos(c.cosSpread);
        node.power[i] = c.power;
        node.child[i] = child;
        if (c.second == 0) node.leaves |= 1u << i;
    }
    return index;
}

void LightTree::importance(const Node& node, glm::vec3 p, glm::vec3 n, float out[4]) const {
    const Float4 zero(0.0f), one(1.0f);
    const Float4 vx = Float4(p.x) - Float4::load(node.centreX),
                 vy = Float4(p.y) - Float4::load(node.centreY),
                 vz = Float4(p.z) - Float4::load(node.centreZ);
    const Float4 d2 = vx * vx + vy * vy + vz * vz;
    const Float4 radius2 = Float4::load(node.radius2);
    // The directions from p to a box lie within angle B of the direction to its centre (its
    // bounding sphere's); inside the sphere they can be anything (B = pi).
    const Float4 outside = greater(d2, radius2);
    const Float4 sin2B = min(radius2 / max(d2, Float4(kMinDistance2)), one);
    const Float4 sinB = select(outside, sqrt(sin2B), zero);
    const Float4 cosB = select(outside, sqrt(one - sin2B), Float4(-1.0f));
    const Float4 len = sqrt(d2);
    const Float4 atCentre = lessEqual(len, zero);
    const Float4 inv = select(atCentre, zero, one / max(len, Float4(kMinDistance2)));
    const Float4 wx = vx * inv, wy = vy * inv, wz = vz * inv;  // from the lights toward p
    // The best emitting cosine toward p of any light below: cos(max(0, W - O - B)), with W the
    // angle between the cone's axis and w and O the cone's spread.
    const Float4 cosO = Float4::load(node.cosSpread), sinO = Float4::load(node.sinSpread);
    const Float4 cosW = Float4::load(node.axisX) * wx + Float4::load(node.axisY) * wy +
                        Float4::load(node.axisZ) * wz;
    const Float4 sinW = sqrt(max(zero, one - cosW * cosW));
    const Float4 withinO = greater(cosW, cosO);
    const Float4 cosX = select(withinO, one, cosW * cosO + sinW * sinO);
    const Float4 sinX = select(withinO, zero, sinW * cosO - cosW * sinO);
    Float4 emitted = select(greater(cosX, cosB), one, cosX * cosB + sinX * sinB);
    emitted = select(lessEqual(cosO, Float4(-1.0f)) | atCentre, one, emitted);
    // The best receiving cosine at p toward any light below: cos(max(0, I - B)).
    Float4 received = one;
    if (glm::dot(n, n) > 0) {
        const Float4 cosI = zero - (Float4(n.x) * wx + Float4(n.y) * wy + Float4(n.z) * wz);
        const Float4 sinI = sqrt(max(zero, one - cosI * cosI));
        received = select(greater(cosI, cosB), one, cosI * cosB + sinI * sinB);
        received = select(atCentre, one, received);
    }
    const Float4 power = Float4::load(node.power);
    const Float4 value = power * emitted * received / max(max(d2, radius2), Float4(kMinDistance2));
    // Zero where a light cannot reach (either cosine not positive) or there is no power.
    const Float4 live = greater(emitted, zero) & greater(received, zero) & greater(power, zero);
    select(live, value, zero).store(out);
}

bool LightTree::sample(glm::vec3 p, glm::vec3 n, float u, std::uint32_t& light, float& probability,
                       Memo* memo) const {
    if (empty()) return false;
    std::uint32_t index = 0;
    float prob = 1;
    for (;;) {
        const Node& node = nodes_[index];
        Weighed weighed;
        const Weighed* at = memo ? memo->find(index) : nullptr;
        if (!at) {
            importance(node, p, n, weighed.weights);
            const float* w = weighed.weights;
            const float total = (w[0] + w[1]) + (w[2] + w[3]);
            if (!(total > 0)) return false;
            // The four shares in one division of four lanes (each lane as the scalar division).
            (Float4::load(w) / Float4(total)).store(weighed.shares);
            if (memo) memo->add(index, weighed);
            at = &weighed;
        }
        const float* w = at->weights;
        const float* shares = at->shares;
        // The child whose share of [0, 1) holds u; u rescaled within that share.
        int i = 0;
        float below = 0;
        for (; i < 3; ++i) {
            const float share = shares[i];
            if (share > 0 && u < below + share) break;
            below += share;
        }
        while (!(w[i] > 0)) --i;  // only rounding at u -> 1 lands past the last live child
        const float share = shares[i];
        u = std::clamp((u - below) / share, 0.0f, kOneBelow);
        prob *= share;
        if (node.leaves & (1u << i)) {
            light = node.child[i];
            break;
        }
        index = node.child[i];
    }
    probability = prob;
    return prob > 0;
}

float LightTree::probability(glm::vec3 p, glm::vec3 n, std::uint32_t light) const {
    if (light >= leafNode_.size()) return 0;
    float prob = 1;
    std::uint32_t index = leafNode_[light], slot = leafSlot_[light];
    for (;;) {
        const Node& node = nodes_[index];
        float w[4];
        importance(node, p, n, w);
        const float total = (w[0] + w[1]) + (w[2] + w[3]);
        if (!(total > 0)) return 0;
        prob *= w[slot] / total;
        if (index == 0) return prob;
        slot = node.slot;
        index = node.parent;
    }
}

}  // namespace igi
