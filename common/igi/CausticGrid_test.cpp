#include "igi/CausticGrid.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "sampling/Hash.h"

namespace igi {
namespace {

std::vector<std::size_t> bruteForce(const std::vector<CausticPhoton>& photons, glm::vec3 p,
                                    float r) {
    std::vector<std::size_t> result;
    for (std::size_t i = 0; i < photons.size(); ++i) {
        const glm::vec3 d = photons[i].position - p;
        if (d.x * d.x + d.y * d.y + d.z * d.z <= r * r) result.push_back(i);
    }
    return result;
}

// Photons carry their index in power.x so results can be compared as sets of indices.
std::vector<std::size_t> gridSearch(const CausticGrid& grid, glm::vec3 p) {
    std::vector<std::size_t> result;
    grid.forEachNear(p,
                     [&](const CausticPhoton& ph) { result.push_back(std::size_t(ph.power.x)); });
    std::sort(result.begin(), result.end());
    return result;
}

void expectSameAsBruteForce(const std::vector<CausticPhoton>& photons, float r,
                            const std::vector<glm::vec3>& queries) {
    const CausticGrid grid(photons, r);
    for (glm::vec3 q : queries)
        EXPECT_EQ(gridSearch(grid, q), bruteForce(photons, q, r))
            << q.x << " " << q.y << " " << q.z;
}

TEST(CausticGrid, MatchesBruteForceAroundTheOriginWithNegativeCoordinates) {
    SplitMix64 rng(42);
    std::vector<CausticPhoton> photons;
    for (int i = 0; i < 3000; ++i)
        photons.push_back(
            {glm::vec3(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2),
             glm::vec3(0, -1, 0), glm::vec3(float(i), 0, 0)});
    std::vector<glm::vec3> queries;
    for (int i = 0; i < 500; ++i)
        queries.push_back(glm::vec3(rng.uniform() * 4.4f - 2.2f, rng.uniform() * 4.4f - 2.2f,
                                    rng.uniform() * 4.4f - 2.2f));
    expectSameAsBruteForce(photons, 0.3f, queries);
    expectSameAsBruteForce(photons, 0.05f, queries);
}

TEST(CausticGrid, FindsPhotonsOnCellFacesAndAtExactlyTheRadius) {
    // r = 0.5: cells are 1 wide, so integer coordinates lie on cell faces and edges.
    std::vector<CausticPhoton> photons;
    int index = 0;
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y)
            for (int z = -3; z <= 3; ++z)
                for (float h : {0.0f, 0.5f})
                    photons.push_back({glm::vec3(x + h, y, z - h), glm::vec3(0),
                                       glm::vec3(float(index++), 0, 0)});
    std::vector<glm::vec3> queries;
    for (int x = -3; x <= 3; ++x)
        for (float f : {0.0f, 0.5f, -0.5f, 0.25f}) queries.push_back(glm::vec3(x + f, f, -x - f));
    expectSameAsBruteForce(photons, 0.5f, queries);
    // A photon at exactly distance r on a cell face is found.
    const CausticGrid grid({{glm::vec3(1.0f, 0, 0), glm::vec3(0), glm::vec3(0)}}, 0.5f);
    EXPECT_EQ(gridSearch(grid, glm::vec3(0.5f, 0, 0)).size(), 1u);
    EXPECT_EQ(gridSearch(grid, glm::vec3(-0.5f, 0, 0)).size(), 0u);
}

TEST(CausticGrid, FarFromTheOriginAndWithCollidingBuckets) {
    // Few photons: a small table, so distinct cells share buckets; each photon is reported once.
    std::vector<CausticPhoton> photons;
    for (int i = 0; i < 5; ++i)
        photons.push_back({glm::vec3(-1e5f + float(i) * 0.01f, 3e4f, -7e4f), glm::vec3(0),
                           glm::vec3(float(i), 0, 0)});
    const std::vector<glm::vec3> queries = {glm::vec3(-1e5f, 3e4f, -7e4f),
                                            glm::vec3(-1e5f + 0.02f, 3e4f, -7e4f)};
    expectSameAsBruteForce(photons, 0.02f, queries);
    expectSameAsBruteForce(photons, 1.0f, queries);
}

TEST(CausticGrid, EmptyGridFindsNothing) {
    const CausticGrid grid({}, 1.0f);
    EXPECT_TRUE(gridSearch(grid, glm::vec3(0)).empty());
}

}  // namespace
}  // namespace igi
