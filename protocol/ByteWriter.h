#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "ProtocolError.h"

namespace igi::proto {

/// Appends little-endian fields to a byte vector. Strings and blobs are a u32 length followed
/// by their bytes.
class ByteWriter {
  public:
    explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}

    void u8(std::uint8_t v) { out_.push_back(v); }
    void u16(std::uint16_t v) { little(v, 2); }
    void u32(std::uint32_t v) { little(v, 4); }
    void u64(std::uint64_t v) { little(v, 8); }
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void boolean(bool v) { u8(v ? 1 : 0); }

    void bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
    void blob(std::span<const std::uint8_t> b) {
        u32(checkedLength(b.size()));
        bytes(b);
    }
    void string(std::string_view s) {
        u32(checkedLength(s.size()));
        out_.insert(out_.end(), s.begin(), s.end());
    }

    std::size_t size() const { return out_.size(); }
    /// The vector written to, for appending in place (compression).
    std::vector<std::uint8_t>& buffer() { return out_; }

  private:
    void little(std::uint64_t v, int n) {
        for (int i = 0; i < n; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    static std::uint32_t checkedLength(std::size_t n) {
        if (n > std::numeric_limits<std::uint32_t>::max())
            throw ProtocolError("a string or blob of " + std::to_string(n) +
                                " bytes does not fit a u32 length");
        return static_cast<std::uint32_t>(n);
    }

    std::vector<std::uint8_t>& out_;
};

}  // namespace igi::proto
