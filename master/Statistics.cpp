#include "Statistics.h"

#include <fstream>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>
#include <nlohmann/json.hpp>

namespace igi {

namespace {

nlohmann::json frameJson(const FrameStats& f) {
    nlohmann::json j = {
        {"index", f.index},
        {"seconds", f.seconds},
        {"composite_seconds", f.compositeSeconds},
        {"decode_seconds", f.decodeSeconds},
        {"epoch", f.epoch},
        {"accumulated", f.accumulated},

        {"rays", f.rays},
        {"shadow_rays", f.shadowRays},
        {"shadow_rays_per_pixel", f.pixels ? double(f.shadowRays) / double(f.pixels) : 0.0},
        {"wire_bytes", f.wireBytes},
        {"wire_bytes_per_pixel", f.pixels ? double(f.wireBytes) / double(f.pixels) : 0.0},
        {"pixels", f.pixels},
        {"tiles", f.tiles},
        {"duplicate_tiles", f.duplicateTiles},
        {"tiles_left_out", f.tilesLeftOut},
        {"sets_built", f.setsBuilt},
        {"vpls", f.vplsPerSet},
        {"caustic_photons", f.photonsPerSet}};
    j["estimated_rel_mse"] = f.estimatedRelMse ? nlohmann::json(*f.estimatedRelMse) : nullptr;
    if (f.framesToTarget) j["predicted_frames_to_target"] = *f.framesToTarget;
    if (f.secondsToTarget) j["predicted_seconds_to_target"] = *f.secondsToTarget;
    if (!f.settings.empty()) j["settings"] = nlohmann::json::parse(f.settings);
    return j;
}

}  // namespace

Statistics::~Statistics() {
    if (framesPath_.empty()) return;
    framesOut_.close();
    std::error_code ignored;
    std::filesystem::remove(framesPath_, ignored);
}

std::filesystem::path Statistics::framesFile(const std::filesystem::path& path) {
    return std::filesystem::path(path.string() + ".frames.jsonl");
}

void Statistics::streamFramesFor(const std::filesystem::path& path) {
    framesPath_ = framesFile(path);
    if (framesPath_.has_parent_path())
        std::filesystem::create_directories(framesPath_.parent_path());
    framesOut_.open(framesPath_, std::ios::trunc);
    if (!framesOut_) throw std::runtime_error(framesPath_.string() + ": cannot write statistics");
}

void Statistics::closeFrame(std::uint32_t index) {
    closedBelow_ = std::max(closedBelow_, index + 1);
    for (auto& [id, c] : clients_) {
        const auto sets = c.setsByOpenFrame.find(index);
        if (sets == c.setsByOpenFrame.end()) continue;
        ++c.frames;
        c.setsInFrames += sets->second.size();
        if (c.firstFrame < 0 || index < c.firstFrame) c.firstFrame = index;
        c.setsByOpenFrame.erase(sets);
    }
    vplSum_.erase(index);
    photonSum_.erase(index);
    const auto it = frames_.find(index);
    if (it == frames_.end()) return;
    if (it->second.shown) {
        ++shownFrames_;
        // One line per frame (through the stream's buffer, a few KB behind): while the session
        // runs, the sidecar is its record so far, in JSON lines.
        if (framesOut_.is_open()) framesOut_ << frameJson(it->second).dump() << '\n';
    }
    frames_.erase(it);
}

FrameStats& Statistics::frame(std::uint32_t index) {
    FrameStats& f = frames_[index];
    f.index = index;
    return f;
}

ClientStats& Statistics::client(ClientId id) {
    ClientStats& c = clients_[id];
    c.id = id;
    return c;
}

void Statistics::addTile(std::uint32_t frameIndex, ClientId clientId, const proto::TileStats& tile,
                         std::uint64_t wireBytes, std::uint32_t pixels) {
    FrameStats& f = frame(frameIndex);
    ClientStats& c = client(clientId);
    f.rays += tile.rays;
    f.shadowRays += tile.shadowRays;
    f.wireBytes += wireBytes;
    f.setsBuilt += tile.setsBuilt;
    f.pixels += pixels;
    ++f.tiles;
    c.rays += tile.rays;
    c.bytes += wireBytes;
    c.renderSeconds += tile.renderSeconds;
    ++c.tiles;
    vplSum_[frameIndex] += tile.vpls;
    photonSum_[frameIndex] += tile.causticPhotons;
    f.vplsPerSet = double(vplSum_[frameIndex]) / f.tiles;
    f.photonsPerSet = double(photonSum_[frameIndex]) / f.tiles;
}

void Statistics::addDuplicate(std::uint32_t frameIndex, ClientId clientId,
                              std::uint64_t wireBytes) {
    client(clientId).bytes += wireBytes;
    if (frameIndex < closedBelow_) return;  // its frame is written and forgotten
    FrameStats& f = frame(frameIndex);
    ++f.duplicateTiles;
    f.wireBytes += wireBytes;
}

void Statistics::noteAssignment(std::uint32_t frameIndex, ClientId clientId, int k) {
    client(clientId).setsByOpenFrame[frameIndex].insert(k);
}

void Statistics::noteFrameDone(double seconds) {
    doneTimes_.push_back(seconds);
    if (doneTimes_.size() > 16) doneTimes_.pop_front();
}

double Statistics::recentFps() const {
    if (doneTimes_.size() < 2) return 0.0;
    const double span = doneTimes_.back() - doneTimes_.front();
    return span > 0 ? double(doneTimes_.size() - 1) / span : 0.0;
}

RecentRates::Totals Statistics::totals() const {
    RecentRates::Totals t;
    for (const auto& [id, c] : clients_) {
        t.bytes += c.bytes;
        if (c.left) continue;  // no rates for clients that are gone
        t.rays[id] = c.rays;
        t.tiles[id] = c.tiles;
    }
    return t;
}

void Statistics::noteTime(double seconds) {
    recent_.sample(seconds, totals());
}

Statistics::Rates Statistics::sampleRates(double seconds) const {
    return recent_.rates(seconds, totals());
}

double Statistics::fps(double totalSeconds) const {
    std::uint64_t shown = shownFrames_;
    for (const auto& [index, f] : frames_) shown += f.shown;
    return totalSeconds > 0 ? double(shown) / totalSeconds : 0.0;
}

std::string Statistics::summaryLine(std::uint32_t index) const {
    const auto it = frames_.find(index);
    if (it == frames_.end()) return {};
    const FrameStats& f = it->second;
    const double mrays = f.seconds > 0 ? double(f.rays) / f.seconds * 1e-6 : 0.0;
    const double bpp = f.pixels ? double(f.wireBytes) / double(f.pixels) : 0.0;
    return fmt::format(
               "frame {:4d}: {:7.1f} ms, {:6.1f} Mrays/s, {:5.1f} shadow rays/px, {:4.2f} B/px, "
               "{} tiles ({} duplicate), {} sets built, master decode {:.1f} ms + "
               "filter/accumulate "
               "{:.1f} ms",
               f.index, f.seconds * 1e3, mrays,
               f.pixels ? double(f.shadowRays) / double(f.pixels) : 0.0, bpp, f.tiles,
               f.duplicateTiles, f.setsBuilt, f.decodeSeconds * 1e3, f.compositeSeconds * 1e3) +
           (f.estimatedRelMse ? fmt::format(", est. relMSE {:.3g}", *f.estimatedRelMse) : "") +
           (f.tilesLeftOut ? fmt::format(", {} tiles left out (under the target)", f.tilesLeftOut)
                           : "");
}

void Statistics::writeJson(const std::filesystem::path& path, const nlohmann::json& session,
                           double renderStart, double renderEnd) {
    const double totalSeconds = renderEnd - renderStart;
    if (framesPath_.empty()) streamFramesFor(path);
    while (!frames_.empty()) closeFrame(frames_.begin()->first);
    for (auto& [id, c] : clients_)
        while (!c.setsByOpenFrame.empty()) closeFrame(c.setsByOpenFrame.begin()->first);
    framesOut_.close();
    if (!framesOut_) throw std::runtime_error(framesPath_.string() + ": cannot write statistics");

    nlohmann::json clients = nlohmann::json::array();
    for (const auto& [id, c] : clients_) {
        // Busy: its threads' render time over its thread count; idle: the rest of the time it
        // was there while frames were rendered.
        const double from = std::max(renderStart, c.readySeconds);
        const double to = c.leftSeconds >= 0 ? std::min(renderEnd, c.leftSeconds) : renderEnd;
        const double busy = c.renderSeconds / std::max(1u, c.threads);
        clients.push_back({{"id", c.id},
                           {"host", c.host},
                           {"peer", c.peer},
                           {"threads", c.threads},
                           {"tiles", c.tiles},
                           {"rays", c.rays},
                           {"bytes", c.bytes},
                           {"render_seconds", c.renderSeconds},
                           {"busy_seconds", busy},
                           {"idle_seconds", std::max(0.0, to - from - busy)},
                           {"frames", c.frames},
                           {"first_frame", c.firstFrame},
                           {"distinct_sets_per_frame",
                            c.frames ? double(c.setsInFrames) / double(c.frames) : 0.0},
                           {"left", c.left},
                           {"leave_reason", c.leaveReason}});
    }
    const nlohmann::json rest{{"clients", clients},
                              {"fps", fps(totalSeconds)},
                              {"seconds", totalSeconds},
                              {"session", session}};
    // The frames are copied line by line from the sidecar, never held in memory together: a
    // session of days has millions of them. The rest is one object whose opening brace is
    // replaced by the frames' array.
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    {
        std::ofstream out(path);
        std::ifstream in(framesPath_);
        if (!out || !in) throw std::runtime_error(path.string() + ": cannot write statistics");
        out << "{\n  \"frames\": [";
        std::string line;
        for (bool first = true; std::getline(in, line); first = false)
            out << (first ? "\n    " : ",\n    ") << line;
        const std::string tail = rest.dump(2);  // "{\n  \"clients\": ..."
        out << "\n  ],\n" << tail.substr(2) << '\n';
        if (!out) throw std::runtime_error(path.string() + ": cannot write statistics");
    }
    std::error_code ignored;
    std::filesystem::remove(framesPath_, ignored);
    framesPath_.clear();
}

}  // namespace igi
