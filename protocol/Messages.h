#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "render/RenderSettings.h"
#include "render/TileChannels.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "scene/SceneChange.h"
#include "scene/SceneLoader.h"

namespace igi::proto {

/// Every message starts with this fixed 24-byte header (little-endian):
///   u32 magic 'IGIP', u16 version, u16 type, u32 frame, u32 epoch, u32 payload size,
///   u32 reserved (0).
/// The frame and the scene epoch travel in every message so that results of an older frame or
/// epoch can be recognised and dropped. The payload size is checked against the type's maximum
/// before anything is allocated.
constexpr std::uint32_t kMagic = 0x50494749u;  // bytes 'I' 'G' 'I' 'P'
constexpr std::uint16_t kVersion = 14;
constexpr std::size_t kHeaderSize = 24;

enum class MessageType : std::uint16_t {
    Hello = 1,         ///< client -> master, first message
    Welcome = 2,       ///< master -> client, answer to Hello
    SceneData = 3,     ///< master -> client: the scene bundle and the settings to render it with
    SceneReady = 4,    ///< client -> master: the scene is built, tiles may come
    TileAssign = 5,    ///< master -> client: render one tile
    TileResult = 6,    ///< client -> master: one tile's pixels
    Heartbeat = 7,     ///< either way, keeps an idle connection known alive
    Shutdown = 8,      ///< master -> client: the session is over, exit
    Error = 9,         ///< either way: a reason, then the sender closes
    SceneUpdate = 10,  ///< master -> client: changes that make the header's epoch
    Challenge = 11,    ///< master -> client, first message: a nonce to prove the secret with
};

/// Nonces and proofs of the handshake (HMAC-SHA256 outputs, net/ClusterKey.h).
using AuthBytes = std::array<std::uint8_t, 32>;

struct Header {
    std::uint16_t version = kVersion;
    MessageType type = MessageType::Heartbeat;
    std::uint32_t frame = 0;
    std::uint32_t epoch = 0;
    std::uint32_t payloadSize = 0;
};

/// The client's answer to a Challenge: who it is, its own nonce, and (unless the cluster runs
/// without a secret) its proof of the secret over both nonces.
struct Hello {
    std::uint16_t protocolVersion = kVersion;
    std::string buildId;
    std::uint32_t threads = 0;
    std::string hostname;
    AuthBytes nonce{};
    std::optional<AuthBytes> proof;
};

/// The master's acceptance, with its own proof of the secret over both nonces, so a client
/// knows it talks to its cluster's master before it takes any work from it.
struct Welcome {
    std::uint32_t clientId = 0;
    std::uint64_t sessionSeed = 0;
    std::optional<AuthBytes> proof;
};

/// The master's first words to a new connection: what it runs and a fresh nonce.
struct Challenge {
    std::uint16_t protocolVersion = kVersion;
    std::string buildId;
    bool secretRequired = true;  ///< false only for a master run with --insecure
    AuthBytes nonce{};
};

/// The scene as files (so a client parses the same bytes as the master) plus what the master's
/// command line changed: the settings, image size and camera to render with.
/// One epoch of a session's history: the changes that make it from the epoch before, and the
/// frame it began at.
struct EpochChanges {
    std::uint32_t firstFrame = 0;
    std::vector<SceneChange> changes;
    bool operator==(const EpochChanges&) const = default;
};

/// The most epochs of history a SceneData carries.
constexpr std::uint32_t kMaxHistoryEpochs = 65536;
/// The epochs a client keeps, the newest: tiles of frames still open may render older epochs
/// than the newest (at most four frames are open at once). The master gives a client no tile
/// of an epoch older than these.
constexpr std::uint32_t kClientKeptEpochs = 8;

struct SceneData {
    SceneBundle bundle;
    RenderSettings settings;
    ImageSettings image;
    Camera camera;
    /// Applied right after loading (and after `camera`): the state of the base epoch, the
    /// header's epoch minus history.size(), which began at frame `baseFirstFrame`.
    std::vector<SceneChange> changes;
    std::uint32_t baseFirstFrame = 0;
    /// The epochs after the base, in order, up to the header's: what a GI mode that keeps
    /// lighting across epochs replays to hold what the other clients hold (docs/MODES.md).
    /// Empty for modes without such state: the client starts in the master's current state.
    std::vector<EpochChanges> history;
};

struct SceneReady {
    std::uint64_t triangles = 0;
    float buildSeconds = 0;
};

/// A tile: the pixels of interleaving cell (kx, ky) inside an image region. Region corners are
/// multiples of the interleaving size, so pixel (x, y) of the region belongs to the tile when
/// (x - x0) % n == kx and (y - y0) % m == ky.
struct TileAssign {
    std::uint32_t tileId = 0;
    std::uint16_t x0 = 0, y0 = 0, width = 0, height = 0;
    std::uint16_t kx = 0, ky = 0;
    /// The frame's place in its accumulation: 0 for the first frame after a change (or for
    /// every frame without accumulation), i for the (i+1)-th frame averaged since. It drives
    /// the progressive parts of the estimator (photon radius, clamp), so it must come from the
    /// master: a client's own history would make the image depend on who rendered what.
    std::uint32_t accumulation = 0;
};

/// Work counters of one tile, summed by the master into statistics.
struct TileStats {
    std::uint64_t rays = 0;            ///< every ray traced for the tile
    std::uint64_t shadowRays = 0;      ///< of which shadow rays
    std::uint32_t vpls = 0;            ///< VPLs in the set the tile used
    std::uint32_t causticPhotons = 0;  ///< photons in the set the tile used
    std::uint32_t setsBuilt = 0;       ///< sets (P_k, C_k) this tile had to build first
    float renderSeconds = 0;
};

struct TileResult {
    std::uint32_t tileId = 0;
    TileStats stats;
    TileChannels channels;  ///< quantized and compressed on the wire
};

/// Applying `changes`, in order, to the scene state of epoch e - 1 gives the state of epoch e,
/// the epoch in the header. The master sends it to every client before any TileAssign of
/// epoch e.
struct SceneUpdate {
    std::vector<SceneChange> changes;
};

struct Heartbeat {};
struct Shutdown {};
struct Error {
    std::string reason;
};

/// In the order of the type numbers: typeOf(m) is m.index() + 1.
using Message = std::variant<Hello, Welcome, SceneData, SceneReady, TileAssign, TileResult,
                             Heartbeat, Shutdown, Error, SceneUpdate, Challenge>;

}  // namespace igi::proto
