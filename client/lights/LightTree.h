#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// Chooses one of many lights for a receiving point by an estimate of what each could give it
/// there, not by power alone (Estevez and Kulla 2018, "Importance Sampling of Many Lights with
/// Adaptive Tree Splitting"; Conty Estevez and Kulla's bounds as in pbrt-v4's BVHLightSampler):
/// a binary tree over the lights whose nodes bound their lights' positions (a box), emitting
/// directions (a cone) and power. At each node the walk takes a child with probability
/// proportional to the child's importance at the point: power x the best cosine any of its lights
/// could have toward the point x the best cosine at the receiver / squared distance.
///
/// The importance only steers the choice: it is zero only where no light below the node can
/// reach the point's front side, so every light that contributes keeps a non-zero probability
/// and the estimate stays unbiased. pdf() gives the exact probability of a choice, for multiple
/// importance sampling. Both are functions of the point and the numbers given only: any client
/// makes the same choice for the same pixel.
class LightTree {
  public:
    /// What the tree needs of one light: where it is, which way it emits, how much.
    struct Light {
        glm::vec3 lo{0.0f}, hi{0.0f};  ///< bounds of its points (lo == hi for a point light)
        glm::vec3 normal{0.0f};        ///< a one-sided emitter's normal; unused when omni
        bool omni = false;             ///< emits in every direction (a point light)
        float power = 0;               ///< emitted power (luminance); 0 is never chosen
    };

    LightTree() = default;
    explicit LightTree(const std::vector<Light>& lights);

    bool empty() const { return nodes_.empty(); }

    /// A node's four children at a point: their weights, and each one's share of their sum.
    struct Weighed {
        float weights[4];
        float shares[4];
    };
    /// The weighed nodes a point's walks visited, so that its next walks (a point takes
    /// several light samples) need not weigh them again, nor divide by their sums. For one p
    /// and n only.
    class Memo {
      public:
        const Weighed* find(std::uint32_t node) const {
            for (int i = 0; i < size_; ++i)
                if (nodes_[i] == node) return &weighed_[i];
            return nullptr;
        }
        void add(std::uint32_t node, const Weighed& w) {
            if (size_ == kSize) return;
            nodes_[size_] = node;
            weighed_[size_] = w;
            ++size_;
        }

      private:
        static constexpr int kSize = 12;
        int size_ = 0;
        std::uint32_t nodes_[kSize];
        Weighed weighed_[kSize];
    };

    /// Chooses a light for the point p with unit normal n (only its front side receives; a zero
    /// n receives from everywhere) with u in [0, 1). False when no light can reach the point.
    /// `memo`, if given, must have been used for this p and n only; the choice is the same.
    bool sample(glm::vec3 p, glm::vec3 n, float u, std::uint32_t& light, float& probability,
                Memo* memo = nullptr) const;

    /// The probability with which sample() chooses `light` for p and n.
    float probability(glm::vec3 p, glm::vec3 n, std::uint32_t light) const;

  private:
    // Built as a binary tree (median splits), then stored with up to four children per node
    // (each binary node's grandchildren), so that one walk step weighs four children in one
    // pass of four lanes: half the steps of the binary walk, each as cheap as one child's.
    struct Binary {
        glm::vec3 lo{0.0f}, hi{0.0f};
        glm::vec3 axis{0.0f, 0.0f, 1.0f};  ///< the cone of emitting normals
        float cosSpread = 1;               ///< cos of its half-angle; -1: every direction
        float power = 0;
        std::uint32_t second = 0;  ///< second child (the first follows the node); 0 for a leaf
        std::uint32_t light = 0;   ///< a leaf's light
    };
    struct Node {  ///< four children, lane by lane; unused lanes have no power
        // Each child's box as importance() reads it, computed once when the tree is built
        // rather than at every weighing: its centre 0.5 (lo + hi) and a quarter of its squared
        // diagonal, the radius^2 of its bounding sphere (the same operations, so the same bits).
        float centreX[4], centreY[4], centreZ[4], radius2[4];
        float axisX[4], axisY[4], axisZ[4], cosSpread[4], sinSpread[4], power[4];
        std::uint32_t child[4];  ///< a node's index, or a light's where `leaves` has the bit
        std::uint32_t leaves = 0;
        std::uint32_t parent = 0;  ///< the node whose child this is (the root's: itself)
        std::uint32_t slot = 0;    ///< which child of it
    };

    std::uint32_t buildBinary(std::vector<Binary>& tree, std::vector<std::uint32_t>& order,
                              std::size_t begin, std::size_t end, const std::vector<Light>& lights);
    std::uint32_t collapse(const std::vector<Binary>& tree, std::uint32_t binary,
                           std::uint32_t parent, std::uint32_t slot);
    /// The four children's importance at p for the receiving normal n.
    void importance(const Node& node, glm::vec3 p, glm::vec3 n, float out[4]) const;

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> leafNode_, leafSlot_;  ///< each light's node and lane
};

}  // namespace igi
