#include "modes/photonmap/PhotonEmission.h"

#include <algorithm>

#include "sampling/HaltonPaths.h"

namespace igi {

EmissionTracer::EmissionTracer(const LightingSetBuilder& builder,
                               std::shared_ptr<const SceneState> state,
                               const RenderSettings& settings)
    : builder_(builder),
      state_(std::move(state)),
      seed_(settings.seed),
      groups_(std::uint32_t(std::max(1, settings.photonmapGroups))),
      photons_(std::uint32_t(std::max(1, settings.photonmapPhotons))) {}

EmissionGroup EmissionTracer::trace(std::uint32_t g, std::uint32_t frame, RayCounters& rays) const {
    EmissionGroup group;
    group.index = g;
    group.tracedFrame = frame;
    group.paths.resize(photons_);
    const HaltonPaths photons(seed_, groups_, g, 0, photons_);
    // traceLightPaths gives each hit its photon's flux / P; the emission holds G groups.
    const float share = 1.0f / float(groups_);
    std::uint32_t photon = 0;
    builder_.traceLightPaths(
        photons, LightingSetBuilder::PathEnd::Roulette, true, rays,
        [&](const Vpl& v) {
            Vpl hit = v;
            hit.power *= share;
            hit.glossyPower *= share;
            group.hits.push_back(hit);
        },
        [&](std::uint32_t j, const SurfacePoint& hit) {
            photon = j;
            PhotonPath& p = group.paths[photon];
            p.meshes.push_back(hit.mesh);
            p.triangles.push_back(hit.triangle);
            p.positions.push_back(hit.position);
        });
    return group;
}

PhotonPath EmissionTracer::path(std::uint32_t g, std::uint32_t c, RayCounters& rays) const {
    PhotonPath p;
    // Photon c alone: the same Halton index, so the same path as in its group's trace.
    const HaltonPaths photon(seed_, groups_, g, c, 1);
    builder_.traceLightPaths(
        photon, LightingSetBuilder::PathEnd::Roulette, true, rays, [](const Vpl&) {},
        [&](std::uint32_t, const SurfacePoint& hit) {
            p.meshes.push_back(hit.mesh);
            p.triangles.push_back(hit.triangle);
            p.positions.push_back(hit.position);
        });
    return p;
}

std::shared_ptr<const PhotonEmission> PhotonEmission::traceAll(const EmissionTracer& tracer,
                                                               std::uint32_t frame) {
    auto all = std::make_shared<PhotonEmission>();
    for (std::uint32_t g = 0; g < tracer.groups(); ++g)
        all->groups_.push_back(
            std::make_shared<const EmissionGroup>(tracer.trace(g, frame, all->update_.rays)));
    all->update_.traced = tracer.groups();
    all->state_ = tracer.state();
    all->lightingSince_ = frame;
    return all;
}

std::shared_ptr<const PhotonEmission> PhotonEmission::step(const EmissionTracer& tracer,
                                                           std::uint32_t frame) const {
    if (settled(*tracer.state(), frame, tracer.photons())) return shared_from_this();
    auto next = std::make_shared<PhotonEmission>(*this);
    next->update_ = {};
    next->state_ = tracer.state();
    if (!state_->sameLighting(*tracer.state())) next->lightingSince_ = frame;
    // A light or a material that changed changes the power every photon carries, though its
    // path may be the same: every group is traced again (the paper moves objects only).
    const bool relit = !state_->sameLightsAndMaterials(*tracer.state());
    // Round robin: every group checks the same photon this frame.
    const std::uint32_t c = frame % tracer.photons();
    for (std::uint32_t g = 0; g < groups_.size(); ++g) {
        ++next->update_.checked;
        if (!relit && tracer.path(g, c, next->update_.rays) == groups_[g]->paths[c]) continue;
        next->groups_[g] =
            std::make_shared<const EmissionGroup>(tracer.trace(g, frame, next->update_.rays));
        ++next->update_.traced;
    }
    if (next->update_.traced > 0) ++next->version_;
    return next;
}

std::vector<Vpl> PhotonEmission::hits() const {
    std::vector<Vpl> out;
    for (const auto& g : groups_) out.insert(out.end(), g->hits.begin(), g->hits.end());
    return out;
}

}  // namespace igi
