#include "TileRenderer.h"

#include <array>
#include <atomic>
#include <chrono>
#include <future>
#include <mutex>

#include "lighting/IgiLighting.h"
#include "math/Warp.h"
#include "modes/cache/CacheLighting.h"
#include "modes/photonmap/PhotonMapLighting.h"
#include "modes/photonmap/ScreenCaustics.h"
#include "modes/spt/SelectiveLighting.h"
#include "modes/stream/StreamLighting.h"

namespace igi {
namespace {

// A chunk is a block of the tile's strided pixel grid, so that the 16 rays of a packet (eye rays,
// or shadow rays to one VPL) leave from points close together in the image: small enough to
// balance the load over the threads, large enough to fill packets and amortize.
constexpr int kChunkColumns = 8, kChunkRows = 8;
constexpr int kChunkPixels = kChunkColumns * kChunkRows;

int chunkCount(const Tile& tile, int n, int m) {
    const int columns = tile.columns(n), rows = tile.rows(m);
    return ((columns + kChunkColumns - 1) / kChunkColumns) * ((rows + kChunkRows - 1) / kChunkRows);
}

// A pixel of a chunk: its index in the tile (row-major in the tile's strided grid) and its
// column and row there.
struct ChunkPixel {
    int index, column, row;
};

// The tile's pixels in chunk c; returns their number. The grid's column and row come with each
// index, so the image coordinates (Tile::columnX/rowY) cost no division per pixel, as
// Tile::pixelX/Y's do.
int chunkPixels(const Tile& tile, int n, int m, int c, ChunkPixel* pixels) {
    const int columns = tile.columns(n), rows = tile.rows(m);
    const int across = (columns + kChunkColumns - 1) / kChunkColumns;
    const int x0 = (c % across) * kChunkColumns, y0 = (c / across) * kChunkRows;
    int count = 0;
    for (int y = y0; y < std::min(rows, y0 + kChunkRows); ++y)
        for (int x = x0; x < std::min(columns, x0 + kChunkColumns); ++x)
            pixels[count++] = {y * columns + x, x, y};
    return count;
}

std::unique_ptr<LightingMethod> makeLightingMethod(
    const LightingSetBuilder& builder, const TraceableScene& scene, const SceneState& state,
    const RenderSettings& settings, const ImageSettings& image, const LightingContext& context) {
    if (settings.integrator == IntegratorKind::Path) return std::make_unique<IgiLighting>(builder);
    switch (settings.gi) {
        case GiMode::Stream:
            return std::make_unique<StreamLighting>(builder, scene, state, settings, context);
        case GiMode::Spt:
            return std::make_unique<SelectiveLighting>(builder, state, settings, context);
        case GiMode::Cache:
            return std::make_unique<CacheLighting>(builder, scene, state, settings, context);
        case GiMode::PhotonMap:
            return std::make_unique<PhotonMapLighting>(builder, scene, state, settings, image,
                                                       context);
        case GiMode::Igi:
            break;
    }
    return std::make_unique<IgiLighting>(builder);
}

}  // namespace

struct TileRenderer::TileJob {
    std::uint32_t frame = 0;
    std::uint32_t accumulation = 0;
    std::uint32_t tileId = 0;
    Tile tile;
    TileChannels channels;
    std::atomic<int> remaining{0};
    std::mutex mutex;  // guards stats
    proto::TileStats stats;
    Done done;
};

TileRenderer::TileRenderer(const TraceableScene& scene, const SceneState& state,
                           const RenderSettings& settings, const ImageSettings& image,
                           const LightingContext& context)
    : scene_(scene),
      settings_(settings),
      image_(image),
      camera_(state.camera, image.width, image.height),
      lights_(scene, state.punctualLights, settings.lightSampling),
      builder_(scene, lights_, settings),
      method_(makeLightingMethod(builder_, scene, state, settings, image, context)),
      cache_(*method_),
      igi_(scene, lights_, settings, camera_),
      path_(scene, lights_, settings, camera_) {
    const RenderSettings first = settings.firstFrameSettings(lights_.count());
    if (!(first == settings))
        firstFrame_ = std::make_unique<FirstFrame>(scene, lights_, first, igi_);
}

void TileRenderer::render(ThreadPool& pool, std::uint32_t frame, std::uint32_t accumulation,
                          std::uint32_t tileId, const Tile& tile, Done done) {
    auto job = std::make_shared<TileJob>();
    job->frame = frame;
    job->accumulation = accumulation;
    job->tileId = tileId;
    job->tile = tile;
    job->done = std::move(done);
    const int count = tile.pixelCount(settings_.interleaveX, settings_.interleaveY);
    const bool path = settings_.integrator == IntegratorKind::Path;
    job->channels.resize(count, path ? std::uint32_t(kUnfiltered) : kAllChannels);
    const int chunks =
        count > 0 ? chunkCount(tile, settings_.interleaveX, settings_.interleaveY) : 0;
    job->remaining = chunks;
    if (chunks == 0) {
        job->done(proto::TileResult{tileId, job->stats, std::move(job->channels)});
        return;
    }
    for (int c = 0; c < chunks; ++c) {
        pool.submit([this, job, c] {
            renderChunk(*job, c);
            if (job->remaining.fetch_sub(1) == 1)
                job->done(proto::TileResult{job->tileId, job->stats, std::move(job->channels)});
        });
    }
}

proto::TileResult TileRenderer::renderNow(ThreadPool& pool, std::uint32_t frame, const Tile& tile,
                                          std::uint32_t accumulation) {
    std::promise<proto::TileResult> promise;
    auto future = promise.get_future();
    render(pool, frame, accumulation, 0, tile,
           [&promise](proto::TileResult&& r) { promise.set_value(std::move(r)); });
    return future.get();
}

void TileRenderer::renderChunk(TileJob& job, int chunk) {
    const auto start = std::chrono::steady_clock::now();
    const int n = settings_.interleaveX, m = settings_.interleaveY;
    RayCounters counters;
    proto::TileStats local;
    TileChannels& out = job.channels;
    ChunkPixel chunkPixel[kChunkPixels];
    const int count = chunkPixels(job.tile, n, m, chunk, chunkPixel);
    if (settings_.integrator == IntegratorKind::Path) {
        for (int k = 0; k < count; ++k) {
            const int i = chunkPixel[k].index;
            const int x = job.tile.columnX(chunkPixel[k].column, n),
                      y = job.tile.rowY(chunkPixel[k].row, m);
            out.unfiltered[i] =
                path_.shade(x, y, std::uint32_t(y * image_.width + x), job.frame, counters);
        }
    } else {
        bool built = false;
        const auto set =
            cacheFor(job.accumulation)
                .get(job.frame, job.accumulation, std::uint32_t(job.tile.setIndex(n)), built);
        const IgiIntegrator& igi = rendersFirstFrame(job.accumulation) ? firstFrame_->igi : igi_;
        if (built) {
            local.setsBuilt = 1;
            counters += set->buildRays;
        }
        local.vpls = std::uint32_t(set->exact.size() + set->direct.size() +
                                   set->directNumbers.size() + set->indirect.size());
        local.causticPhotons =
            std::uint32_t(set->caustics.photons().size() + set->indirectCaustics.photons().size());
        // Per thread, not on the stack: arrays of structs with member initializers would be
        // cleared for every chunk (4.5 KB), and shade() sets each result it uses anyway.
        thread_local std::array<IgiIntegrator::Pixel, kChunkPixels> pixels;
        thread_local std::array<PixelResult, kChunkPixels> results;
        for (int k = 0; k < count; ++k) {
            const int x = job.tile.columnX(chunkPixel[k].column, n),
                      y = job.tile.rowY(chunkPixel[k].row, m);
            pixels[k] = {x, y, std::uint32_t(y * image_.width + x)};
        }
        igi.shade(pixels.data(), count, job.frame, *set, results.data(), counters);
        for (int k = 0; k < count; ++k) {
            const int i = chunkPixel[k].index, x = pixels[k].x, y = pixels[k].y;
            PixelResult& r = results[k];
            if (set->screenCaustics && r.firstHit) {
                const ScreenCaustics& c = *set->screenCaustics;
                r.irradiance +=
                    kInvPi * c.irradiance(x, y, c.footprint(x, y, r.depth, r.normal), counters);
            }
            out.irradiance[i] = r.irradiance;
            out.reflectance[i] = r.reflectance;
            out.normal[i] = r.normal;
            out.depth[i] = r.depth;
            out.unfiltered[i] = r.unfiltered;
            out.glossy[i] = r.glossy;
        }
    }
    const float seconds =
        std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard lock(job.mutex);
    job.stats.renderSeconds += seconds;  // busy time of the threads, not time spent queued
    job.stats.rays += counters.rays;
    job.stats.shadowRays += counters.shadowRays;
    job.stats.setsBuilt += local.setsBuilt;
    job.stats.vpls = std::max(job.stats.vpls, local.vpls);
    job.stats.causticPhotons = std::max(job.stats.causticPhotons, local.causticPhotons);
}

}  // namespace igi
