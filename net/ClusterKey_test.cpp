#include "net/ClusterKey.h"
#include "util/TestPaths.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace igi::net {
namespace {

TEST(ClusterKey, ProofsAgreeOnlyWithTheSameSecretAndNonces) {
    const ClusterKey a = ClusterKey::fromSecret("correct horse battery staple");
    const ClusterKey same = ClusterKey::fromSecret("correct horse battery staple");
    const ClusterKey other = ClusterKey::fromSecret("correct horse battery staplf");
    const auto m = ClusterKey::randomNonce(), c = ClusterKey::randomNonce();
    EXPECT_TRUE(ClusterKey::same(a.clientProof(m, c), same.clientProof(m, c)));
    EXPECT_FALSE(ClusterKey::same(a.clientProof(m, c), other.clientProof(m, c)));
    // Roles differ: a client's proof is no master's proof, and the nonces' order matters.
    EXPECT_FALSE(ClusterKey::same(a.clientProof(m, c), a.masterProof(m, c)));
    EXPECT_FALSE(ClusterKey::same(a.clientProof(m, c), a.clientProof(c, m)));
    // A fresh nonce makes a fresh proof: an old one cannot be replayed.
    EXPECT_FALSE(
        ClusterKey::same(a.clientProof(m, c), a.clientProof(ClusterKey::randomNonce(), c)));
    EXPECT_NE(ClusterKey::randomNonce(), ClusterKey::randomNonce());
}

TEST(ClusterKey, ShortSecretsAreRefusedAndFilesAreRead) {
    EXPECT_THROW(ClusterKey::fromSecret("short"), std::invalid_argument);
    const auto file = testing::scratchPath("secret");
    std::ofstream(file) << "a secret long enough to use\n";
    const auto m = ClusterKey::randomNonce(), c = ClusterKey::randomNonce();
    EXPECT_TRUE(
        ClusterKey::same(ClusterKey::fromFile(file).clientProof(m, c),
                         ClusterKey::fromSecret("a secret long enough to use").clientProof(m, c)));
    std::filesystem::remove(file);
    EXPECT_THROW(ClusterKey::fromFile("/nonexistent/igi-secret"), std::invalid_argument);
    EXPECT_GE(ClusterKey::randomSecret().size(), ClusterKey::kMinSecretBytes);
}

}  // namespace
}  // namespace igi::net
