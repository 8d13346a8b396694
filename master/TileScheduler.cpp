#include "TileScheduler.h"

#include <algorithm>
#include <stdexcept>

namespace igi {
namespace {

// A client that has not completed a tile yet (it may be building its first light sets) is
// allowed this long before its tiles are copied to others.
constexpr double kUnmeasuredLatency = 1.0;

}  // namespace

TileScheduler::TileScheduler(std::vector<Tile> layout, int setCount)
    : layout_(std::move(layout)), setCount_(setCount) {
    // Queue index of each tile: its k, numbered in the order the layout first shows it.
    std::map<std::pair<int, int>, int> setOf;
    for (const Tile& t : layout_) {
        auto [it, fresh] = setOf.try_emplace({t.ky, t.kx}, int(setOf.size()));
        setQueue_.push_back(it->second);
    }
    setCount_ = std::max(setCount_, int(setOf.size()));
}

void TileScheduler::openFrame(std::uint32_t frame, const std::vector<bool>* leftOut) {
    if (!frames_.empty() && frame <= frames_.rbegin()->first)
        throw std::logic_error("frames must be opened in increasing order");
    if (leftOut && leftOut->size() != layout_.size())
        throw std::logic_error("openFrame: tiles left out of another layout");
    FrameState f;
    f.tiles.resize(layout_.size());
    f.pendingBySet.resize(std::size_t(setCount_));
    for (std::uint32_t i = 0; i < layout_.size(); ++i) {
        if (leftOut && (*leftOut)[i]) {
            f.tiles[i].state = State::Done;  // never handed out: the frame is done without it
            ++f.done;
            continue;
        }
        f.pendingBySet[std::size_t(setQueue_[i])].push_back(i);
        ++f.pending;
    }
    frames_.emplace(frame, std::move(f));
}

std::vector<std::uint32_t> TileScheduler::openFrames() const {
    std::vector<std::uint32_t> result;
    for (const auto& [frame, f] : frames_) result.push_back(frame);
    return result;
}

std::optional<Assignment> TileScheduler::next(ClientId client, double minDuplicateAge,
                                              std::uint32_t firstFrame) {
    for (auto& [frame, f] : frames_)
        if (frame >= firstFrame && f.pending > 0) return takePending(client, frame, f);
    return takeDuplicate(client, minDuplicateAge, firstFrame);
}

int TileScheduler::chooseSet(ClientId client, const FrameState& f) const {
    const auto current = currentSet_.find(client);
    if (current != currentSet_.end() && !f.pendingBySet[std::size_t(current->second)].empty())
        return current->second;
    // Another k: the one fewest other clients are on, then the one with most tiles left.
    std::vector<int> sharing(f.pendingBySet.size(), 0);
    for (const auto& [other, k] : currentSet_)
        if (other != client) ++sharing[std::size_t(k)];
    int best = -1;
    for (int k = 0; k < int(f.pendingBySet.size()); ++k) {
        if (f.pendingBySet[std::size_t(k)].empty()) continue;
        if (best < 0 || sharing[std::size_t(k)] < sharing[std::size_t(best)] ||
            (sharing[std::size_t(k)] == sharing[std::size_t(best)] &&
             f.pendingBySet[std::size_t(k)].size() > f.pendingBySet[std::size_t(best)].size()))
            best = k;
    }
    return best;
}

std::optional<Assignment> TileScheduler::takePending(ClientId client, std::uint32_t frame,
                                                     FrameState& f) {
    const int k = chooseSet(client, f);
    if (k < 0) return std::nullopt;
    currentSet_[client] = k;
    auto& queue = f.pendingBySet[std::size_t(k)];
    const std::uint32_t tile = queue.front();
    queue.pop_front();
    --f.pending;
    give(client, frame, tile, f);
    return Assignment{frame, tile, false};
}

std::optional<Assignment> TileScheduler::takeDuplicate(ClientId client, double minAge,
                                                       std::uint32_t firstFrame) {
    const auto now = std::chrono::steady_clock::now();
    // The oldest frame first: it is the one holding the output back.
    for (auto& [frame, f] : frames_) {
        if (frame < firstFrame) continue;
        for (std::uint32_t i = 0; i < f.tiles.size(); ++i) {
            TileState& t = f.tiles[i];
            // One spare copy per tile is enough to get past one slow client.
            if (t.state != State::InFlight || t.holders.size() >= 2 || t.holders.count(client))
                continue;
            bool late = true;
            for (const auto& [holder, since] : t.holders) {
                const auto measured = latency(holder);
                const double allowed =
                    std::max(minAge, measured ? 3.0 * *measured : kUnmeasuredLatency);
                late &= std::chrono::duration<double>(now - since).count() >= allowed;
            }
            if (!late) continue;
            give(client, frame, i, f);
            return Assignment{frame, i, true};
        }
    }
    return std::nullopt;
}

void TileScheduler::give(ClientId client, std::uint32_t frame, std::uint32_t tile, FrameState& f) {
    f.tiles[tile].state = State::InFlight;
    f.tiles[tile].holders[client] = std::chrono::steady_clock::now();
    held_[client].insert({frame, tile});
}

std::optional<double> TileScheduler::latency(ClientId client) const {
    const auto it = latency_.find(client);
    if (it == latency_.end()) return std::nullopt;
    return it->second;
}

bool TileScheduler::complete(ClientId client, std::uint32_t frame, std::uint32_t tile) {
    auto it = frames_.find(frame);
    if (it == frames_.end() || tile >= it->second.tiles.size()) return false;
    TileState& t = it->second.tiles[tile];
    // Only a client that holds the tile may complete it: a result for a tile it was never given
    // (or that someone else finished first) is dropped.
    if (t.state != State::InFlight || !t.holders.count(client)) return false;
    t.state = State::Done;
    ++it->second.done;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t.holders[client]).count();
    auto [entry, fresh] = latency_.try_emplace(client, seconds);
    if (!fresh) entry->second = 0.8 * entry->second + 0.2 * seconds;
    // Other holders of a copy keep rendering it; their results will be dropped.
    for (const auto& [holder, since] : t.holders) held_[holder].erase({frame, tile});
    t.holders.clear();
    return true;
}

void TileScheduler::reopen(std::uint32_t frame, std::uint32_t tile) {
    auto it = frames_.find(frame);
    if (it == frames_.end() || tile >= it->second.tiles.size()) return;
    FrameState& f = it->second;
    TileState& t = f.tiles[tile];
    if (t.state != State::Done) return;
    t.state = State::Pending;
    --f.done;
    f.pendingBySet[std::size_t(setQueue_[tile])].push_front(tile);
    ++f.pending;
}

int TileScheduler::releaseClient(ClientId client) {
    int released = 0;
    auto held = held_.find(client);
    if (held != held_.end()) {
        for (auto [frame, tile] : held->second) {
            FrameState& f = frames_.at(frame);
            TileState& t = f.tiles[tile];
            t.holders.erase(client);
            if (t.state != State::InFlight || !t.holders.empty()) continue;
            // Back to the front of its k's queue: it is the oldest work there.
            t.state = State::Pending;
            f.pendingBySet[std::size_t(setQueue_[tile])].push_front(tile);
            ++f.pending;
            ++released;
        }
        held_.erase(held);
    }
    currentSet_.erase(client);
    latency_.erase(client);
    return released;
}

void TileScheduler::closeFrame(std::uint32_t frame) {
    frames_.erase(frame);
    for (auto& [client, tiles] : held_)
        for (auto it = tiles.begin(); it != tiles.end();)
            it = it->first == frame ? tiles.erase(it) : std::next(it);
}

bool TileScheduler::frameDone(std::uint32_t frame) const {
    auto it = frames_.find(frame);
    return it != frames_.end() && it->second.done == int(it->second.tiles.size());
}

bool TileScheduler::frameFullyAssigned(std::uint32_t frame) const {
    auto it = frames_.find(frame);
    return it != frames_.end() && it->second.pending == 0;
}

int TileScheduler::inFlight(ClientId client) const {
    auto it = held_.find(client);
    return it == held_.end() ? 0 : int(it->second.size());
}

}  // namespace igi
