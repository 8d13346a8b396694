#include "JoinerScene.h"

#include <spdlog/spdlog.h>

namespace igi {

void prepareJoinerScene(proto::SceneData& data, const SceneTimeline& timeline, ClientId client) {
    SceneTimeline::Join join = timeline.join();
    data.changes = std::move(join.changes);
    data.baseFirstFrame = join.baseFirstFrame;
    data.history.clear();
    for (auto& e : join.history) data.history.push_back({e.firstFrame, std::move(e.changes)});
    // The GI mode in force, which a settings command may have changed.
    const GiMode gi = timeline.state().render.gi;
    if ((gi == GiMode::Spt || gi == GiMode::PhotonMap) && !timeline.historyComplete())
        spdlog::warn(
            "client {} joins at epoch {}, past the {} epochs of history a joiner replays: its "
            "photon groups start from epoch {}, so its tiles may be lit differently from the "
            "other clients' (docs/MODES.md)",
            client, timeline.epoch(), proto::kMaxHistoryEpochs,
            timeline.epoch() - data.history.size());
}

}  // namespace igi
