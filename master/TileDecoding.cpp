#include "TileDecoding.h"

#include <chrono>
#include <exception>

#include <boost/asio/post.hpp>

#include "Codec.h"

namespace igi {

void decodeTileOnPool(ThreadPool& pool, boost::asio::io_context& io, OpenFrames::Frame& frame,
                      const Tile& tile, const proto::Header& header,
                      std::vector<std::uint8_t> payload, DecodedTile decoded,
                      std::function<void(const DecodedTile&)> done) {
    pool.submit([&io, record = &frame, tile, header, payload = std::move(payload),
                 decoded = std::move(decoded), done = std::move(done)]() mutable {
        const auto start = std::chrono::steady_clock::now();
        try {
            // Decompressed and copied into the frame still quantized: the compositor
            // dequantizes the codes as it filters them (CodedFrame.h). A result refused here
            // has written nothing.
            const auto result = proto::decodeTileResultCodes(header, payload);
            record->buffer.scatter(tile, result.codes);  // checks the pixel count first
            decoded.stats = result.stats;
        } catch (const std::exception& e) {
            decoded.error = std::string("bad tile result: ") + e.what();
        }
        decoded.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        boost::asio::post(
            io, [done = std::move(done), decoded = std::move(decoded)] { done(decoded); });
    });
}

}  // namespace igi
