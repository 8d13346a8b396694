#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "Messages.h"

namespace igi::net {

/// The shared secret of a render cluster, and the challenge-response built on it.
///
/// At connect the master sends a fresh random nonce; the client answers with its own nonce and
/// HMAC-SHA256(key, "igi client" | master nonce | client nonce); the master checks it and answers
/// with HMAC-SHA256(key, "igi master" | client nonce | master nonce). Each side thus proves it
/// holds the key before the other gives it anything (a scene, a tile, a result), and neither
/// proof can be replayed, the other side's nonce being fresh. The key is BLAKE2b-256 of the
/// secret (libsodium), so a secret of any length works.
class ClusterKey {
  public:
    /// At least this many bytes of secret are required: a short one could be guessed.
    static constexpr std::size_t kMinSecretBytes = 16;

    /// From a secret; throws std::invalid_argument if it is shorter than kMinSecretBytes.
    static ClusterKey fromSecret(const std::string& secret);
    /// From a file's contents (trailing newlines dropped); throws naming the file.
    static ClusterKey fromFile(const std::filesystem::path& file);
    /// A random secret, for a master that starts its own local clients only.
    static std::string randomSecret();

    proto::AuthBytes clientProof(const proto::AuthBytes& masterNonce,
                                 const proto::AuthBytes& clientNonce) const;
    proto::AuthBytes masterProof(const proto::AuthBytes& masterNonce,
                                 const proto::AuthBytes& clientNonce) const;
    /// Constant-time comparison of a received proof with the expected one.
    static bool same(const proto::AuthBytes& a, const proto::AuthBytes& b);

    static proto::AuthBytes randomNonce();

  private:
    explicit ClusterKey(const proto::AuthBytes& key) : key_(key) {}
    proto::AuthBytes mac(const char* role, const proto::AuthBytes& first,
                         const proto::AuthBytes& second) const;

    proto::AuthBytes key_;
};

/// Where a process finds its cluster secret: --secret-file, else the IGI_SECRET environment
/// variable. Returns nothing when neither is given.
std::optional<ClusterKey> clusterKeyFrom(const std::filesystem::path& secretFile);

}  // namespace igi::net
