#include "net/ClusterKey.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <sodium.h>

namespace igi::net {
namespace {

void initSodium() {
    static const bool ready = sodium_init() >= 0;
    if (!ready) throw std::runtime_error("libsodium could not be initialised");
}

}  // namespace

ClusterKey ClusterKey::fromSecret(const std::string& secret) {
    if (secret.size() < kMinSecretBytes)
        throw std::invalid_argument("the cluster secret has " + std::to_string(secret.size()) +
                                    " bytes; at least " + std::to_string(kMinSecretBytes) +
                                    " are needed");
    initSodium();
    proto::AuthBytes key;
    crypto_generichash(key.data(), key.size(),
                       reinterpret_cast<const unsigned char*>(secret.data()), secret.size(),
                       nullptr, 0);
    return ClusterKey(key);
}

ClusterKey ClusterKey::fromFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::invalid_argument(file.string() + ": cannot read the cluster secret");
    std::stringstream s;
    s << in.rdbuf();
    std::string secret = s.str();
    while (!secret.empty() && (secret.back() == '\n' || secret.back() == '\r')) secret.pop_back();
    try {
        return fromSecret(secret);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(file.string() + ": " + e.what());
    }
}

std::string ClusterKey::randomSecret() {
    initSodium();
    unsigned char bytes[32];
    randombytes_buf(bytes, sizeof bytes);
    char hex[2 * sizeof bytes + 1];
    sodium_bin2hex(hex, sizeof hex, bytes, sizeof bytes);
    return hex;
}

proto::AuthBytes ClusterKey::randomNonce() {
    initSodium();
    proto::AuthBytes n;
    randombytes_buf(n.data(), n.size());
    return n;
}

proto::AuthBytes ClusterKey::mac(const char* role, const proto::AuthBytes& first,
                                 const proto::AuthBytes& second) const {
    static_assert(crypto_auth_hmacsha256_KEYBYTES == std::tuple_size_v<proto::AuthBytes>);
    static_assert(crypto_auth_hmacsha256_BYTES == std::tuple_size_v<proto::AuthBytes>);
    crypto_auth_hmacsha256_state state;
    crypto_auth_hmacsha256_init(&state, key_.data(), key_.size());
    crypto_auth_hmacsha256_update(&state, reinterpret_cast<const unsigned char*>(role),
                                  std::strlen(role));
    crypto_auth_hmacsha256_update(&state, first.data(), first.size());
    crypto_auth_hmacsha256_update(&state, second.data(), second.size());
    proto::AuthBytes out;
    crypto_auth_hmacsha256_final(&state, out.data());
    return out;
}

proto::AuthBytes ClusterKey::clientProof(const proto::AuthBytes& masterNonce,
                                         const proto::AuthBytes& clientNonce) const {
    return mac("igi client v1", masterNonce, clientNonce);
}

proto::AuthBytes ClusterKey::masterProof(const proto::AuthBytes& masterNonce,
                                         const proto::AuthBytes& clientNonce) const {
    return mac("igi master v1", clientNonce, masterNonce);
}

bool ClusterKey::same(const proto::AuthBytes& a, const proto::AuthBytes& b) {
    return sodium_memcmp(a.data(), b.data(), a.size()) == 0;
}

std::optional<ClusterKey> clusterKeyFrom(const std::filesystem::path& secretFile) {
    if (!secretFile.empty()) return ClusterKey::fromFile(secretFile);
    if (const char* env = std::getenv("IGI_SECRET")) return ClusterKey::fromSecret(env);
    return std::nullopt;
}

}  // namespace igi::net
