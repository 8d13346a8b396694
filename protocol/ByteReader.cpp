#include "ByteReader.h"

#include <bit>

#include "ProtocolError.h"

namespace igi::proto {

float ByteReader::f32() {
    return std::bit_cast<float>(u32());
}

bool ByteReader::boolean() {
    const std::uint8_t v = u8();
    if (v > 1) fail("boolean byte is " + std::to_string(v) + ", expected 0 or 1");
    return v == 1;
}

std::span<const std::uint8_t> ByteReader::bytes(std::size_t n) {
    need(n);
    auto out = bytes_.subspan(pos_, n);
    pos_ += n;
    return out;
}

std::span<const std::uint8_t> ByteReader::blob() {
    const std::uint32_t n = u32();
    return bytes(n);  // checked against what remains before anyone copies it
}

std::string ByteReader::string() {
    auto b = blob();
    return std::string(b.begin(), b.end());
}

void ByteReader::expectEnd() const {
    if (remaining() != 0)
        throw ProtocolError(std::to_string(remaining()) + " trailing bytes after " + what_ +
                            " payload (" + std::to_string(pos_) + " bytes were expected)");
}

void ByteReader::fail(const std::string& message) const {
    throw ProtocolError(what_ + ": " + message);
}

std::uint64_t ByteReader::little(int n) {
    need(static_cast<std::size_t>(n));
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint64_t{bytes_[pos_ + i]} << (8 * i);
    pos_ += static_cast<std::size_t>(n);
    return v;
}

void ByteReader::need(std::size_t n) const {
    if (n > remaining())
        throw ProtocolError("truncated " + what_ + ": needed " + std::to_string(n - remaining()) +
                            " more bytes at offset " + std::to_string(pos_));
}

}  // namespace igi::proto
