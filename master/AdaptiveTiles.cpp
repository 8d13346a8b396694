#include "AdaptiveTiles.h"

#include <stdexcept>

namespace igi {

AdaptiveTiles::AdaptiveTiles(std::vector<Tile> layout, int width, int height, int n, int m,
                             int tileSize, std::uint32_t lag)
    : layout_(std::move(layout)),
      all_(width, height, n, m, tileSize),
      lag_(lag),
      width_(width),
      height_(height),
      n_(n),
      m_(m),
      tileSize_(tileSize) {}

void AdaptiveTiles::decide(std::uint32_t composited, std::uint32_t epoch, int accumulated,
                           double target, const std::vector<double>& regionErrors) {
    if (target <= 0 || accumulated < kMinFrames) return;  // every region, by default
    if (regionErrors.size() != std::size_t(all_.count()))
        throw std::logic_error("AdaptiveTiles::decide: estimates of another layout's regions");
    Decision d{epoch, all_};
    for (int r = 0; r < d.regions.count(); ++r)
        d.regions.setRendered(r, regionErrors[std::size_t(r)] > target);
    decisions_[composited + lag_] = std::move(d);
}

TileRegions AdaptiveTiles::regionsFor(std::uint32_t frame, std::uint32_t epoch) const {
    const auto it = decisions_.find(frame);
    if (it == decisions_.end() || it->second.epoch != epoch ||
        it->second.regions.renderedCount() == 0)
        return all_;
    return it->second.regions;
}

std::vector<bool> AdaptiveTiles::tilesLeftOut(const TileRegions& regions) const {
    std::vector<bool> out(layout_.size());
    for (std::size_t i = 0; i < layout_.size(); ++i)
        out[i] = !regions.rendered(regions.regionOf(layout_[i]));
    return out;
}

void AdaptiveTiles::prepareCells(proto::CodedFrame& frame, const TileRegions& regions,
                                 const TileRegions& next) {
    if (regions.all() && next.all()) return;
    kept_.reuse(width_, height_, n_, m_, tileSize_);
    for (int r = 0; r < regions.count(); ++r) {
        if (!regions.rendered(r))
            frame.copyRegion(kept_, regions.rectangle(r));
        else if (!next.rendered(r))
            kept_.copyRegion(frame, regions.rectangle(r));
    }
}

void AdaptiveTiles::forgetBefore(std::uint32_t frame) {
    decisions_.erase(decisions_.begin(), decisions_.lower_bound(frame));
}

}  // namespace igi
