#include "modes/spt/PhotonGroups.h"

#include <algorithm>
#include <numeric>

#include "sampling/HaltonPaths.h"

namespace igi {
namespace {

void sortUnique(std::vector<std::uint32_t>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Instances past the scene's meshes are the quad lights' own geometry: a change of theirs is a
// light change.
bool moved(const SceneState& then, const SceneState& now, std::uint32_t mesh) {
    return mesh < then.transforms.size() && then.transforms[mesh] != now.transforms[mesh];
}

bool anyMoved(const SceneState& then, const SceneState& now,
              const std::vector<std::uint32_t>& meshes) {
    return std::any_of(meshes.begin(), meshes.end(),
                       [&](std::uint32_t m) { return moved(then, now, m); });
}

}  // namespace

GroupTracer::GroupTracer(const LightingSetBuilder& builder, std::shared_ptr<const SceneState> state,
                         const RenderSettings& settings)
    : builder_(builder),
      state_(std::move(state)),
      seed_(settings.seed),
      groups_(std::uint32_t(std::max(1, settings.sptGroups))),
      paths_(std::uint32_t(std::max(1, settings.sptPaths))),
      pilots_(std::uint32_t(std::clamp(settings.sptPilots, 1, std::max(1, settings.sptPaths)))) {}

void GroupTracer::tracePaths(std::uint32_t g, std::uint32_t count, RayCounters& rays,
                             PhotonGroup& out) const {
    if (builder_.maxLightPathLength(true) < 2) return;  // no bounce: no indirect light
    const HaltonPaths paths(seed_, groups_, g, 0, count);
    std::uint32_t path = 0;
    // A part of an object (an instance of a glTF file's shared primitive) moves with it: the
    // object's index stands for it.
    const Scene& scene = builder_.scene().geometry().scene();
    // traceLightPaths gives each VPL its path's flux / count; the pool holds G groups.
    const float share = 1.0f / float(groups_);
    builder_.traceLightPaths(
        paths, LightingSetBuilder::PathEnd::Roulette, true, rays,
        [&](const Vpl& v) {
            Vpl scaled = v;
            scaled.power *= share;
            scaled.glossyPower *= share;
            out.vpls.push_back(scaled);
            out.vplPaths.push_back(path);
        },
        [&](std::uint32_t j, const SurfacePoint& hit) {
            path = j;
            out.meshes.push_back(hit.mesh < scene.meshes.size() ? objectOf(scene, hit.mesh)
                                                                : hit.mesh);
        });
    sortUnique(out.meshes);
}

PhotonGroup GroupTracer::trace(std::uint32_t g, std::uint32_t frame, RayCounters& rays) const {
    PhotonGroup group;
    group.index = g;
    group.tracedFrame = frame;
    group.scene = state_;
    tracePaths(g, paths_, rays, group);
    return group;
}

std::vector<std::uint32_t> GroupTracer::pilotMeshes(std::uint32_t g, RayCounters& rays) const {
    PhotonGroup pilots;
    tracePaths(g, pilots_, rays, pilots);
    return pilots.meshes;
}

bool groupTouched(const PhotonGroup& group, const SceneState& now,
                  const std::function<std::vector<std::uint32_t>()>& pilots) {
    const SceneState& then = *group.scene;
    if (!then.sameLightsAndMaterials(now)) return true;
    if (then.transforms == now.transforms) return false;  // the camera alone moved
    if (anyMoved(then, now, group.meshes)) return true;
    return anyMoved(then, now, pilots());
}

std::shared_ptr<const PhotonGroups> PhotonGroups::traceAll(const GroupTracer& tracer,
                                                           std::uint32_t frame) {
    auto pool = std::make_shared<PhotonGroups>();
    for (std::uint32_t g = 0; g < tracer.groups(); ++g)
        pool->groups_.push_back(
            std::make_shared<const PhotonGroup>(tracer.trace(g, frame, pool->update_.rays)));
    pool->invalid_.assign(pool->groups_.size(), false);
    pool->update_.traced = tracer.groups();
    pool->scene_ = tracer.sharedState();
    return pool;
}

std::shared_ptr<const PhotonGroups> PhotonGroups::change(const GroupTracer& tracer,
                                                         std::uint32_t frame,
                                                         std::uint32_t budget) const {
    auto marked = std::make_shared<PhotonGroups>(*this);
    marked->update_ = {};
    marked->scene_ = tracer.sharedState();
    // Every group was checked against a state that lights the scene the same (the camera alone
    // moved): nothing new to detect.
    const bool sameLight = scene_->sameLighting(tracer.state());
    for (std::size_t g = 0; g < groups_.size() && !sameLight; ++g) {
        if (invalid_[g]) continue;
        const bool touched = groupTouched(*groups_[g], tracer.state(), [&] {
            ++marked->update_.pilotGroups;
            return tracer.pilotMeshes(std::uint32_t(g), marked->update_.rays);
        });
        if (touched) {
            marked->invalid_[g] = true;
            ++marked->update_.touched;
        }
    }
    marked->traceOldest(tracer, frame, budget);
    return marked;
}

std::shared_ptr<const PhotonGroups> PhotonGroups::step(const GroupTracer& tracer,
                                                       std::uint32_t frame,
                                                       std::uint32_t budget) const {
    if (invalidCount() == 0) return shared_from_this();
    auto next = std::make_shared<PhotonGroups>(*this);
    next->update_ = {};
    next->scene_ = tracer.sharedState();
    next->traceOldest(tracer, frame, budget);
    return next;
}

void PhotonGroups::traceOldest(const GroupTracer& tracer, std::uint32_t frame,
                               std::uint32_t budget) {
    std::vector<std::uint32_t> waiting;
    for (std::uint32_t g = 0; g < invalid_.size(); ++g)
        if (invalid_[g]) waiting.push_back(g);
    // Oldest first, ties by index: the same order on every client.
    std::stable_sort(waiting.begin(), waiting.end(), [&](std::uint32_t a, std::uint32_t b) {
        return groups_[a]->tracedFrame < groups_[b]->tracedFrame;
    });
    waiting.resize(std::min<std::size_t>(waiting.size(), budget));
    for (std::uint32_t g : waiting) {
        groups_[g] = std::make_shared<const PhotonGroup>(tracer.trace(g, frame, update_.rays));
        invalid_[g] = false;
    }
    update_.traced = std::uint32_t(waiting.size());
}

std::uint32_t PhotonGroups::invalidCount() const {
    return std::uint32_t(std::count(invalid_.begin(), invalid_.end(), true));
}

}  // namespace igi
