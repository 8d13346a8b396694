// igi-bench: how close a client comes to the hardware's limit. On one scene and one machine, side
// by side in one run, it measures
//   - raw Embree occlusion throughput: random shadow segments with rtcOccluded1 and in packets of
//     8 and 16 (rtcOccluded8, rtcOccluded16), on the given number of threads;
//   - a client's throughput rendering whole frames of tiles (IGI, every ray counted);
// and reports the ratio. The two take turns: each round traces its share of the segments raw,
// then renders one frame, and every figure sums its rounds, so a load that comes or goes while
// the bench runs weighs on both sides alike. Results go to stdout as JSON.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <ctime>
#include <functional>
#include <iostream>
#include <mutex>
#include <utility>

#include <embree3/rtcore.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "ShadowSegments.h"
#include "TileRenderer.h"
#include "render/Tile.h"
#include "scene/SceneLoader.h"
#include "scene/SceneState.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"
#include "util/ThreadPool.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kChunk = 4096;

double seconds(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the whole process (every thread): on a machine shared with others, rays per CPU
// second move far less with their load than rays per second of wall time. The calling thread
// only waits while the pool works, so this is the pool's time.
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Wall and CPU seconds of one measurement.
struct Timing {
    Clock::time_point wallStart = Clock::now();
    double cpuStart = processCpuSeconds();
    double wall() const { return seconds(wallStart); }
    double cpu() const { return processCpuSeconds() - cpuStart; }
};

// Calls chunk(c) for every chunk c < count on the pool's threads only, as the client renders
// tiles: ThreadPool::parallelFor would put the calling thread to work as well, one thread more
// than the client gets (which once made the raw figures look twice as fast on one thread).
void forEachChunkOnPool(std::size_t count, igi::ThreadPool& pool,
                        const std::function<void(std::size_t)>& chunk) {
    std::atomic<std::size_t> next{0};
    for (unsigned t = 0; t < pool.size(); ++t)
        pool.submit([&] {
            for (std::size_t c; (c = next.fetch_add(1)) < count;) chunk(c);
        });
    pool.waitIdle();
}

// Rays traced and the wall and CPU seconds they took, summed over rounds.
struct Measured {
    double rays = 0, wall = 0, cpu = 0;
    void add(double traced, const Timing& t) {
        rays += traced;
        wall += t.wall();
        cpu += t.cpu();
    }
    double perSecond() const { return rays / wall; }
    double perCpuSecond() const { return rays / cpu; }
};

// Segments [begin, end) through rtcOccluded1, one ray at a time; returns how many are blocked.
std::size_t occluded1(RTCScene scene, const std::vector<igi::ShadowSegment>& segs,
                      std::size_t begin, std::size_t end, igi::ThreadPool& pool, Measured& into) {
    std::atomic<std::size_t> hits{0};
    const Timing timing;
    forEachChunkOnPool((end - begin + kChunk - 1) / kChunk, pool, [&](std::size_t c) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        std::size_t local = 0;
        for (std::size_t i = begin + c * kChunk; i < std::min(end, begin + (c + 1) * kChunk); ++i) {
            RTCRay ray{};
            ray.org_x = segs[i].origin.x, ray.org_y = segs[i].origin.y,
            ray.org_z = segs[i].origin.z;
            ray.dir_x = segs[i].direction.x, ray.dir_y = segs[i].direction.y,
            ray.dir_z = segs[i].direction.z;
            ray.tnear = 0;
            ray.tfar = segs[i].length;
            ray.mask = 0xFFFFFFFFu;
            rtcOccluded1(scene, &context, &ray);
            local += ray.tfar < 0;
        }
        hits += local;
    });
    into.add(double(end - begin), timing);
    return hits;
}

// Segments [begin, end) through rtcOccluded8 or rtcOccluded16: packets of N consecutive
// segments.
template <int N, typename Packet>
void occludedN(RTCScene scene, const std::vector<igi::ShadowSegment>& segs, std::size_t begin,
               std::size_t end, igi::ThreadPool& pool, Measured& into) {
    const Timing timing;
    forEachChunkOnPool((end - begin + kChunk - 1) / kChunk, pool, [&](std::size_t c) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        const std::size_t last = std::min(end, begin + (c + 1) * kChunk);
        for (std::size_t i = begin + c * kChunk; i < last; i += N) {
            alignas(64) int valid[N];
            alignas(64) Packet ray{};
            for (int j = 0; j < N; ++j) {
                const std::size_t k = i + j;
                valid[j] = k < last ? -1 : 0;
                if (k >= last) continue;
                ray.org_x[j] = segs[k].origin.x, ray.org_y[j] = segs[k].origin.y,
                ray.org_z[j] = segs[k].origin.z;
                ray.dir_x[j] = segs[k].direction.x, ray.dir_y[j] = segs[k].direction.y,
                ray.dir_z[j] = segs[k].direction.z;
                ray.tnear[j] = 0;
                ray.tfar[j] = segs[k].length;
                ray.mask[j] = 0xFFFFFFFFu;
            }
            if constexpr (N == 8)
                rtcOccluded8(valid, scene, &context, &ray);
            else
                rtcOccluded16(valid, scene, &context, &ray);
        }
    });
    into.add(double(end - begin), timing);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-bench: client throughput against raw Embree on the same scene and machine"};
    std::string sceneFile;
    unsigned threads = 0;
    std::size_t segments = 4'000'000;
    int frames = 4, width = 0, height = 0, tilesInFlight = 0;
    bool allowOutsidePaths = false, accumulated = false;
    app.add_option("--scene", sceneFile, "scene file or .obj")->required();
    app.add_flag("--allow-outside-paths", allowOutsidePaths,
                 "let the scene file name files outside its own folder");
    app.add_option("--threads", threads, "threads for both measurements (0: all)")
        ->capture_default_str();
    app.add_option("--segments", segments, "random shadow segments for the raw measurement")
        ->capture_default_str();
    app.add_option("--frames", frames,
                   "rounds: frames the client renders, each after its share of the raw segments")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    app.add_flag("--accumulated", accumulated,
                 "render the frames as frames 1.. of an accumulation (a view held still: the "
                 "converging estimator), not each as the first frame after a change");
    app.add_option("--tiles-in-flight", tilesInFlight,
                   "tiles the client holds at once, as the master's queue depth gives them "
                   "(0: 2 + threads / 8, the depth for tiles slower than 20 ms)")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    app.add_option("--width", width, "image width (0: the scene's)");
    app.add_option("--height", height, "image height (0: the scene's)");
    CLI11_PARSE(app, argc, argv);
    // The JSON is the whole of stdout: scripts read it as it is. Messages (a scene's loading
    // warnings) go to stderr.
    spdlog::set_default_logger(spdlog::stderr_color_mt("igi-bench"));
    spdlog::set_level(spdlog::level::warn);
    try {
        igi::SceneLoadOptions loadOptions;
        loadOptions.allowOutsidePaths = allowOutsidePaths;
        igi::Scene scene = igi::loadSceneFile(sceneFile, loadOptions);
        if (width > 0) scene.image.width = width;
        if (height > 0) scene.image.height = height;
        igi::ThreadPool pool(threads > 0 ? threads : igi::ThreadPool::defaultThreads());
        igi::EmbreeDevice device;
        igi::SceneGeometry geometry(device, scene);
        igi::TraceableScene traceable(geometry);

        const auto segs = igi::randomShadowSegments(traceable, segments, 12345);
        const RTCScene embree = traceable.embreeScene();
        Measured unused, raw1, raw8, raw16, client;  // client.rays: its shadow rays
        std::uint64_t clientRays = 0;
        occluded1(embree, segs, 0, segs.size(), pool, unused);  // warm up caches and threads

        igi::TileRenderer renderer(traceable, igi::SceneState::of(scene), scene.render, scene.image,
                                   igi::LightingContext{&scene, 0, 0, nullptr});
        const auto& s = scene.render;
        const auto tiles = igi::makeTiles(scene.image.width, scene.image.height, s.interleaveX,
                                          s.interleaveY, s.tileSize);
        // A client in a session holds a few tiles at a time (the master's queue depth: at
        // least 2 + threads / 8), so the bench keeps as many in flight and hands out the next
        // when one is done. Handing every tile of a frame out at once allocated all their
        // buffers together and freed them together: glibc gave the freed heap back and the next
        // frame faulted it in again, 15 to 25 % of a small scene's client CPU that a session's
        // client does not pay.
        const std::size_t inFlight =
            std::size_t(tilesInFlight > 0 ? tilesInFlight : 2 + int(pool.size()) / 8);
        // One frame of the client's: its rays and shadow rays.
        auto renderFrame = [&](std::uint32_t f) {
            std::uint64_t rays = 0, shadowRays = 0;
            std::size_t remaining = tiles.size(), next = 0;
            // Recursive: a tile without chunks reports at once, inside render().
            std::recursive_mutex mutex;
            std::condition_variable_any done;
            // Hands out the next tile, if any; called with `mutex` held.
            std::function<void()> handOut = [&] {
                if (next == tiles.size()) return;
                const auto t = std::uint32_t(next++);
                renderer.render(pool, f, accumulated ? f + 1 : 0, t, tiles[t],
                                [&](igi::proto::TileResult&& r) {
                                    std::lock_guard lock(mutex);
                                    rays += r.stats.rays;
                                    shadowRays += r.stats.shadowRays;
                                    handOut();
                                    if (--remaining == 0) done.notify_all();
                                });
            };
            std::unique_lock lock(mutex);
            for (std::size_t k = 0; k < inFlight; ++k) handOut();
            done.wait(lock, [&] { return remaining == 0; });
            return std::pair{rays, shadowRays};
        };
        // The client warms up too (its threads' buffers, the first touch of its memory), with a
        // frame of its own that no round renders again.
        renderFrame(std::uint32_t(frames));

        std::size_t blocked = 0;
        for (int f = 0; f < frames; ++f) {
            const std::size_t begin = segs.size() * std::size_t(f) / std::size_t(frames),
                              end = segs.size() * std::size_t(f + 1) / std::size_t(frames);
            blocked += occluded1(embree, segs, begin, end, pool, raw1);
            occludedN<8, RTCRay8>(embree, segs, begin, end, pool, raw8);
            occludedN<16, RTCRay16>(embree, segs, begin, end, pool, raw16);
            const Timing timing;
            const auto [rays, shadowRays] = renderFrame(std::uint32_t(f));
            client.add(double(shadowRays), timing);
            clientRays += rays;
        }
        const double clientRaysPerSecond = double(clientRays) / client.wall,
                     clientRaysPerCpuSecond = double(clientRays) / client.cpu;

        nlohmann::json out{
            {"scene", sceneFile},
            {"triangles", traceable.triangleCount()},
            {"threads", pool.size()},
            {"segments", segs.size()},
            {"segments_blocked", double(blocked) / double(segs.size())},
            {"rounds", frames},
            {"embree_occluded1_rays_per_second", raw1.perSecond()},
            {"embree_occluded8_rays_per_second", raw8.perSecond()},
            {"embree_occluded16_rays_per_second", raw16.perSecond()},
            {"embree_occluded1_rays_per_cpu_second", raw1.perCpuSecond()},
            {"embree_occluded8_rays_per_cpu_second", raw8.perCpuSecond()},
            {"embree_occluded16_rays_per_cpu_second", raw16.perCpuSecond()},
            {"client_packet_width", traceable.packetWidth()},
            {"scene_layout", traceable.layout() == igi::SceneLayout::Flat ? "flat" : "instanced"},
            {"client_accumulated", accumulated},
            {"client_frames", frames},
            {"client_tiles_in_flight", inFlight},
            {"client_width", scene.image.width},
            {"client_height", scene.image.height},
            {"client_seconds", client.wall},
            {"client_cpu_seconds", client.cpu},
            {"client_rays", clientRays},
            {"client_shadow_rays", std::uint64_t(client.rays)},
            {"client_rays_per_second", clientRaysPerSecond},
            {"client_shadow_rays_per_second", client.perSecond()},
            {"client_rays_per_cpu_second", clientRaysPerCpuSecond},
            {"client_shadow_rays_per_cpu_second", client.perCpuSecond()},
            {"client_rays_over_embree_occluded1", clientRaysPerSecond / raw1.perSecond()},
            {"client_shadow_rays_over_embree_occluded8", client.perSecond() / raw8.perSecond()},
            {"client_shadow_rays_over_embree_occluded16", client.perSecond() / raw16.perSecond()},
            {"client_shadow_rays_over_embree_occluded16_cpu",
             client.perCpuSecond() / raw16.perCpuSecond()}};
        std::cout << out.dump(2) << '\n';
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "igi-bench: " << e.what() << '\n';
        return 1;
    }
}
