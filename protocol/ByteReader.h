#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace igi::proto {

/// Reads little-endian fields from untrusted bytes. Every read is bounds-checked and throws
/// ProtocolError naming the message (`what`) when the bytes run out; a length prefix is checked
/// against the bytes that remain before anything is allocated for it.
class ByteReader {
  public:
    ByteReader(std::span<const std::uint8_t> bytes, std::string_view what)
        : bytes_(bytes), what_(what) {}

    std::uint8_t u8() { return static_cast<std::uint8_t>(little(1)); }
    std::uint16_t u16() { return static_cast<std::uint16_t>(little(2)); }
    std::uint32_t u32() { return static_cast<std::uint32_t>(little(4)); }
    std::uint64_t u64() { return little(8); }
    std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
    float f32();
    bool boolean();

    /// The next `n` bytes, without copying.
    std::span<const std::uint8_t> bytes(std::size_t n);
    /// A u32 length, then that many bytes.
    std::span<const std::uint8_t> blob();
    std::string string();

    std::size_t remaining() const { return bytes_.size() - pos_; }
    std::size_t offset() const { return pos_; }
    const std::string& what() const { return what_; }

    /// Throws when bytes are left over: trailing garbage is as suspicious as missing bytes.
    void expectEnd() const;

    /// Throws ProtocolError "<what>: <message>".
    [[noreturn]] void fail(const std::string& message) const;

  private:
    std::uint64_t little(int n);
    void need(std::size_t n) const;

    std::span<const std::uint8_t> bytes_;
    std::size_t pos_ = 0;
    std::string what_;
};

}  // namespace igi::proto
