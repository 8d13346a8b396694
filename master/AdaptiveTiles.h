#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "CodedFrame.h"
#include "render/Tile.h"
#include "render/TileRegions.h"

namespace igi {

/// Adaptive tiles (docs/ERROR_ESTIMATE.md): with a target error, the tile regions whose
/// estimated error is at or below it are not rendered again until something changes (a new
/// epoch, new settings, a lower target); the frames go to the regions that need them.
///
/// The image must not depend on which client rendered what, nor on timing, so each decision
/// rests only on what the master composited: the regions of frame g are chosen from the image
/// composited after frame g - lag, lag being the number of frames open at once. Frame g can
/// open only once that frame is composited (Master::openFramesAsNeeded), so its decision is
/// always made before it opens, whatever the clients' pace.
///
/// The regions a frame leaves out still need cells: the discontinuity buffer of the pixels
/// beside them reads them. They are filled with the cells of the frame that rendered them last
/// (kept here), the same whoever rendered it; the accumulation then leaves those pixels as they
/// were (FrameCompositor, RowAccumulator::prepareFrame).
class AdaptiveTiles {
  public:
    /// Fewer frames than this give an estimate too noisy to stop a region on (ERROR_ESTIMATE.md:
    /// at 4 to 16 frames it is 0.5x to 0.8x the true error on the boxes with glass or glossy
    /// lobes).
    static constexpr int kMinFrames = 16;

    /// For frames of `layout` (makeTiles(width, height, n, m, tileSize)), `lag` frames open at
    /// once.
    AdaptiveTiles(std::vector<Tile> layout, int width, int height, int n, int m, int tileSize,
                  std::uint32_t lag);

    /// Every region of the layout, rendered.
    const TileRegions& regions() const { return all_; }
    /// Frame `composited` of epoch `epoch` was composited into an accumulation of
    /// `accumulated` frames whose regions' estimates are `regionErrors` (ShownError, in
    /// regions()' order): decides the regions of frame composited + lag, each rendered while its
    /// estimate is above `target` (0: no target, every region).
    void decide(std::uint32_t composited, std::uint32_t epoch, int accumulated, double target,
                const std::vector<double>& regionErrors);
    /// The regions frame `frame` of `epoch` renders: those decided for it if it renders the
    /// epoch they were decided in, else every region (a new epoch starts its accumulation
    /// afresh). Never none: a frame with nothing to render would never finish.
    TileRegions regionsFor(std::uint32_t frame, std::uint32_t epoch) const;
    /// Per tile of the layout: whether `regions` leaves it out.
    std::vector<bool> tilesLeftOut(const TileRegions& regions) const;

    /// Before frame `frame` (rendering `regions`, followed by a frame rendering `next`) is
    /// composited: fills the regions it leaves out with their last rendered cells, and keeps
    /// the cells of those it renders and the next leaves out. On the pool, one frame at a time.
    void prepareCells(proto::CodedFrame& frame, const TileRegions& regions,
                      const TileRegions& next);

    /// Forgets the decisions for frames before `frame`.
    void forgetBefore(std::uint32_t frame);

  private:
    struct Decision {
        std::uint32_t epoch = 0;
        TileRegions regions;
    };

    std::vector<Tile> layout_;
    TileRegions all_;  ///< every region rendered
    std::uint32_t lag_;
    std::map<std::uint32_t, Decision> decisions_;  ///< by the frame they are for
    proto::CodedFrame kept_;                       ///< the last rendered cells of each region
    int width_, height_, n_, m_, tileSize_;
};

}  // namespace igi
