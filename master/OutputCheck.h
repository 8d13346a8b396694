#pragma once

#include <filesystem>
#include <string>

namespace igi {

/// Checks, before the first frame, that a file written at the end (or during the run) can be
/// written: its folder exists or can be made, and takes a new file. A run of many frames must
/// not learn at its end that its output was never possible. Throws std::invalid_argument
/// naming `flag` and the path.
void checkWritableFolder(const std::filesystem::path& path, const std::string& flag);

/// checkWritableFolder, and a type writeImage knows (.png or .exr).
void checkImageOutput(const std::filesystem::path& path, const std::string& flag);

/// checkImageOutput for --error-output, which must be an .exr: relMSE values are linear and
/// mostly far below one, which a tone-mapped .png would show as black.
void checkErrorOutput(const std::filesystem::path& path);

}  // namespace igi
