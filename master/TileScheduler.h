#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "render/Tile.h"

namespace igi {

using ClientId = std::uint32_t;

/// A tile handed to a client: which frame, which tile of that frame's layout.
struct Assignment {
    std::uint32_t frame = 0;
    std::uint32_t tile = 0;
    bool duplicate = false;  ///< a second copy of a tile another client still holds
    bool operator==(const Assignment&) const = default;
};

/// Decides which client renders which tile (paper, section 5.3).
///
/// Every frame has the same tile layout. A client is given tiles of the interleaving set k it
/// already works on, so it builds few sets P_k / C_k per frame; when its k runs out it moves to
/// the k with the most tiles left that fewest clients share. Frames are pipelined: a client
/// that finds nothing left in the oldest frame takes tiles of the next one. When nothing is left
/// to hand out, an idle client gets a copy of a tile still held by another (slow or stalled)
/// client; the first result wins. A client that leaves gives its tiles back.
class TileScheduler {
  public:
    /// `layout` is every frame's tiles; `setCount` the number of interleaving sets n * m.
    TileScheduler(std::vector<Tile> layout, int setCount);

    /// Opens a frame: all its tiles become pending, but those `leftOut` marks (adaptive tiles:
    /// one flag per tile of the layout), which count as done and are never handed out. Frames
    /// must be opened in increasing order.
    void openFrame(std::uint32_t frame, const std::vector<bool>* leftOut = nullptr);
    /// The next tile for `client`, or nothing. Only frames opened so far are considered. A copy
    /// of a tile held elsewhere is given only once it is late: out for at least
    /// `minDuplicateAge` seconds and three times its holder's usual latency (a holder not yet
    /// measured is allowed a second), so that a slower client is not raced for every tile.
    /// Frames before `firstFrame` are not the client's: one that joined holds no epoch older
    /// than the one it got with the scene, and frames opened before then may render one.
    std::optional<Assignment> next(ClientId client, double minDuplicateAge = 0,
                                   std::uint32_t firstFrame = 0);
    /// The holder's usual latency, as measured from its completed tiles (seconds), if any.
    std::optional<double> latency(ClientId client) const;
    /// A result arrived. True if it completes the tile (the first copy); false if the tile was
    /// already done or is unknown (then the result must be dropped).
    bool complete(ClientId client, std::uint32_t frame, std::uint32_t tile);
    /// A completed tile turned out unusable (its result failed to decode): it is pending again.
    void reopen(std::uint32_t frame, std::uint32_t tile);
    /// The client is gone: tiles only it held become pending again. Returns how many.
    int releaseClient(ClientId client);
    /// Forgets a finished frame.
    void closeFrame(std::uint32_t frame);

    bool frameDone(std::uint32_t frame) const;
    /// Whether every tile of `frame` has been handed out at least once.
    bool frameFullyAssigned(std::uint32_t frame) const;
    int inFlight(ClientId client) const;
    const std::vector<Tile>& layout() const { return layout_; }
    std::vector<std::uint32_t> openFrames() const;

  private:
    enum class State : std::uint8_t { Pending, InFlight, Done };
    struct TileState {
        State state = State::Pending;
        /// Who holds a copy, and since when.
        std::map<ClientId, std::chrono::steady_clock::time_point> holders;
    };
    struct FrameState {
        std::vector<TileState> tiles;
        std::vector<std::deque<std::uint32_t>> pendingBySet;  ///< tile indices, per k
        int pending = 0;
        int done = 0;
    };

    std::optional<Assignment> takePending(ClientId client, std::uint32_t frame, FrameState& f);
    std::optional<Assignment> takeDuplicate(ClientId client, double minAge,
                                            std::uint32_t firstFrame);
    int chooseSet(ClientId client, const FrameState& f) const;
    void give(ClientId client, std::uint32_t frame, std::uint32_t tile, FrameState& f);

    std::vector<Tile> layout_;
    std::vector<int> setQueue_;  ///< per tile of the layout: the index of its k's queue
    int setCount_;
    std::map<std::uint32_t, FrameState> frames_;
    std::map<ClientId, int> currentSet_;  ///< the k each client works on
    std::map<ClientId, std::set<std::pair<std::uint32_t, std::uint32_t>>> held_;
    /// Each client's usual time from receiving a tile to its result (moving average).
    std::map<ClientId, double> latency_;
};

}  // namespace igi
