#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "Messages.h"
#include "OpenFrames.h"
#include "TileScheduler.h"
#include "render/Tile.h"
#include "util/ThreadPool.h"

namespace igi {

/// What the io thread learns of a tile result decoded on the pool.
struct DecodedTile {
    ClientId client = 0;
    std::uint32_t frame = 0;
    std::uint32_t tile = 0;  ///< its number in the layout
    std::string error;       ///< empty, or why the result was refused (then it wrote nothing)
    proto::TileStats stats;
    std::uint64_t wireBytes = 0;  ///< the message's size, header included
    double seconds = 0;           ///< pool time spent decoding and scattering it
};

/// Decodes the result `payload` of tile `tile` (`header`, and `decoded`'s client, frame, tile
/// number and wire size) on `pool` into `frame`'s buffer, then posts `done` with the outcome to
/// `io`: session state is only ever touched on the io thread. `frame` must stay open until
/// `done` runs (OpenFrames::Frame::decoding counts the results still out).
void decodeTileOnPool(ThreadPool& pool, boost::asio::io_context& io, OpenFrames::Frame& frame,
                      const Tile& tile, const proto::Header& header,
                      std::vector<std::uint8_t> payload, DecodedTile decoded,
                      std::function<void(const DecodedTile&)> done);

}  // namespace igi
