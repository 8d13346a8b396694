#pragma once

#include <stdexcept>
#include <string>

namespace igi {

/// A user error in a scene file or a file it references. It names the file and, where known,
/// the line (for OBJ/MTL) or the JSON path (for scene files), and says what is wrong.
class SceneError : public std::runtime_error {
  public:
    SceneError(std::string file, int line, std::string jsonPath, std::string message);

    /// Convenience constructors.
    static SceneError atLine(std::string file, int line, std::string message);
    static SceneError atPath(std::string file, std::string jsonPath, std::string message);
    static SceneError inFile(std::string file, std::string message);

    const std::string& file() const { return file_; }
    int line() const { return line_; }  ///< 0 when unknown
    const std::string& jsonPath() const { return jsonPath_; }
    const std::string& message() const { return message_; }

  private:
    std::string file_;
    int line_;
    std::string jsonPath_;
    std::string message_;
};

}  // namespace igi
