#include "Statistics.h"

#include <fstream>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>
#include <nlohmann/json.hpp>

namespace igi {

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
    FrameStats& f = frame(frameIndex);
    ++f.duplicateTiles;
    f.wireBytes += wireBytes;
    client(clientId).bytes += wireBytes;
}

void Statistics::noteAssignment(std::uint32_t frameIndex, ClientId clientId, int k) {
    client(clientId).setsByFrame[frameIndex].insert(k);
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
    std::size_t shown = 0;
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
           (f.estimatedRelMse ? fmt::format(", est. relMSE {:.3g}", *f.estimatedRelMse) : "");
}

void Statistics::writeJson(const std::filesystem::path& path, const nlohmann::json& session,
                           double renderStart, double renderEnd) const {
    const double totalSeconds = renderEnd - renderStart;
    nlohmann::json frames = nlohmann::json::array();
    for (const auto& [index, f] : frames_) {
        if (!f.shown) continue;
        frames.push_back(
            {{"index", f.index},
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
             {"sets_built", f.setsBuilt},
             {"vpls", f.vplsPerSet},
             {"caustic_photons", f.photonsPerSet}});
        const auto orNull = [](const std::optional<double>& v) {
            return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
        };
        frames.back()["estimated_rel_mse"] = orNull(f.estimatedRelMse);
        if (f.framesToTarget) frames.back()["predicted_frames_to_target"] = *f.framesToTarget;
        if (f.secondsToTarget) frames.back()["predicted_seconds_to_target"] = *f.secondsToTarget;
    }
    nlohmann::json clients = nlohmann::json::array();
    for (const auto& [id, c] : clients_) {
        // Busy: its threads' render time over its thread count; idle: the rest of the time it
        // was there while frames were rendered.
        const double from = std::max(renderStart, c.readySeconds);
        const double to = c.leftSeconds >= 0 ? std::min(renderEnd, c.leftSeconds) : renderEnd;
        const double busy = c.renderSeconds / std::max(1u, c.threads);
        std::size_t sets = 0;
        for (const auto& [frame, ks] : c.setsByFrame) sets += ks.size();
        clients.push_back(
            {{"id", c.id},
             {"host", c.host},
             {"peer", c.peer},
             {"threads", c.threads},
             {"tiles", c.tiles},
             {"rays", c.rays},
             {"bytes", c.bytes},
             {"render_seconds", c.renderSeconds},
             {"busy_seconds", busy},
             {"idle_seconds", std::max(0.0, to - from - busy)},
             {"frames", c.setsByFrame.size()},
             {"first_frame",
              c.setsByFrame.empty() ? -1 : std::int64_t(c.setsByFrame.begin()->first)},
             {"distinct_sets_per_frame",
              c.setsByFrame.empty() ? 0.0 : double(sets) / double(c.setsByFrame.size())},
             {"left", c.left},
             {"leave_reason", c.leaveReason}});
    }
    nlohmann::json root{{"frames", frames},
                        {"clients", clients},
                        {"fps", fps(totalSeconds)},
                        {"seconds", totalSeconds},
                        {"session", session}};
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path.string() + ": cannot write statistics");
    out << root.dump(2) << '\n';
}

}  // namespace igi
