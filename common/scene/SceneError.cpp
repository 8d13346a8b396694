#include "scene/SceneError.h"

#include <utility>

namespace igi {

namespace {

// The one format every scene error uses, so that editors can jump to the place:
// "file:line: message" for text formats, "file: /json/path: message" for scene files.
std::string formatWhat(const std::string& file, int line, const std::string& jsonPath,
                       const std::string& message) {
    if (line > 0) return file + ":" + std::to_string(line) + ": " + message;
    if (!jsonPath.empty()) return file + ": " + jsonPath + ": " + message;
    return file + ": " + message;
}

}  // namespace

SceneError::SceneError(std::string file, int line, std::string jsonPath, std::string message)
    : std::runtime_error(formatWhat(file, line, jsonPath, message)),
      file_(std::move(file)),
      line_(line),
      jsonPath_(std::move(jsonPath)),
      message_(std::move(message)) {}

SceneError SceneError::atLine(std::string file, int line, std::string message) {
    return SceneError(std::move(file), line, "", std::move(message));
}

SceneError SceneError::atPath(std::string file, std::string jsonPath, std::string message) {
    return SceneError(std::move(file), 0, std::move(jsonPath), std::move(message));
}

SceneError SceneError::inFile(std::string file, std::string message) {
    return SceneError(std::move(file), 0, "", std::move(message));
}

}  // namespace igi
