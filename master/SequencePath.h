#pragma once

#include <cstdint>
#include <string>

namespace igi {

/// Checks an output-sequence pattern such as "out/frame_%04d.png": exactly one integer
/// conversion (%d, optionally with a zero-padded width), no other '%' but "%%", and an .png or
/// .exr extension. Throws std::invalid_argument saying what is wrong.
void checkSequencePattern(const std::string& pattern);

/// The pattern with the frame number in place of its conversion.
std::string sequencePath(const std::string& pattern, std::uint32_t frame);

}  // namespace igi
