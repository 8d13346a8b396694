#include "modes/stream/PhotonStream.h"

#include "sampling/LightPathSampler.h"

namespace igi {

PhotonBatch shootPhotonBatch(const LightingSetBuilder& builder,
                             const std::vector<SurfaceLight>& lights, std::uint64_t seed,
                             std::uint32_t index, std::uint32_t paths, RayCounters& rays) {
    PhotonBatch batch;
    batch.front.assign(lights.size(), glm::vec3(0.0f));
    batch.back.assign(lights.size(), glm::vec3(0.0f));
    batch.paths = paths;
    const int maxLength = builder.maxLightPathLength(true);
    if (lights.empty() || paths == 0 || maxLength < 2) return batch;
    const LightPathSampler sampler(seed, index, SampleStream::PhotonStream, 0, paths,
                                   std::uint32_t(maxLength));
    // traceLightPaths divides by the paths; the pool sums batches and divides by its own count.
    const float perPath = float(paths);
    builder.traceLightPaths(
        sampler, LightingSetBuilder::PathEnd::Roulette, true, rays, [&](const Vpl& v) {
            const SurfaceLightHit h = nearestSurfaceLight(lights, v.position, v.normal);
            (h.front ? batch.front : batch.back)[h.index] += v.power * perPath;
        });
    return batch;
}

std::shared_ptr<const PhotonStream> PhotonStream::first(
    std::shared_ptr<const std::vector<SurfaceLightSite>> sites, std::uint32_t epoch,
    std::uint32_t firstFrame, int window,
    const std::function<PhotonBatch(std::uint32_t index)>& shoot) {
    auto s = std::make_shared<PhotonStream>();
    s->sites_ = std::move(sites);
    s->epoch_ = epoch;
    const std::uint32_t last = batchIndex(firstFrame);
    for (int i = window - 1; i >= 0; --i)
        s->batches_.push_back(std::make_shared<const PhotonBatch>(shoot(last - std::uint32_t(i))));
    return s;
}

std::shared_ptr<const PhotonStream> PhotonStream::next(
    std::uint32_t epoch, int window, std::shared_ptr<const PhotonBatch> batch) const {
    auto s = std::make_shared<PhotonStream>();
    s->sites_ = sites_;
    s->epoch_ = epoch;
    const std::size_t keep = std::size_t(std::max(0, window - 1));
    const std::size_t from = batches_.size() > keep ? batches_.size() - keep : 0;
    s->batches_.assign(batches_.begin() + std::ptrdiff_t(from), batches_.end());
    s->batches_.push_back(std::move(batch));
    return s;
}

std::uint32_t PhotonStream::paths() const {
    std::uint32_t n = 0;
    for (const auto& b : batches_) n += b->paths;
    return n;
}

void PhotonStream::power(std::vector<glm::vec3>& front, std::vector<glm::vec3>& back) const {
    front.assign(sites_->size(), glm::vec3(0.0f));
    back.assign(sites_->size(), glm::vec3(0.0f));
    const std::uint32_t n = paths();
    if (n == 0) return;
    // Summed in batch order, the same on every client.
    for (const auto& b : batches_)
        for (std::size_t i = 0; i < front.size(); ++i) {
            front[i] += b->front[i];
            back[i] += b->back[i];
        }
    const float inv = 1.0f / float(n);
    for (std::size_t i = 0; i < front.size(); ++i) {
        front[i] *= inv;
        back[i] *= inv;
    }
}

}  // namespace igi
