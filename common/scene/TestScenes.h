#pragma once

// Helpers shared by the scene loader's tests (only *_test.cpp files include this).

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene/FileSource.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"
#include "util/TestPaths.h"

namespace igi::test {

/// An OBJ of one triangle, for scenes whose geometry does not matter.
inline constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

/// common/scene/testdata in the source tree.
inline std::filesystem::path testdataDir() {
    return igi::testing::sourceDir() / "common" / "scene" / "testdata";
}

/// The public test scenes (../shared/scenes next to the project), if present.
inline std::optional<std::filesystem::path> sharedScenesDir() {
    const auto dir = igi::testing::sharedScenesDir();
    if (!std::filesystem::is_directory(dir)) return std::nullopt;
    return dir;
}

/// For test scene files that reach ../shared/scenes: trusted, so they may leave their folder.
inline SceneLoadOptions trusted() {
    SceneLoadOptions options;
    options.allowOutsidePaths = true;
    return options;
}

/// Parses scene text whose referenced files are given in memory.
inline Scene parseInline(const std::string& json, std::map<std::string, std::string> files = {}) {
    BundleFileSource source(std::move(files));
    return parseScene(json, "inline.json", source);
}

/// The what() of the SceneError that `f` throws, or "" (and a test failure) if none.
template <typename F>
std::string sceneErrorOf(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a SceneError";
    return "";
}

/// What the default logger writes while it lives (the loaders warn through it).
class CapturedLog {
  public:
    CapturedLog() : previous_(spdlog::default_logger()) {
        auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
        spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink));
    }
    ~CapturedLog() { spdlog::set_default_logger(previous_); }
    CapturedLog(const CapturedLog&) = delete;
    CapturedLog& operator=(const CapturedLog&) = delete;
    std::string text() const { return text_.str(); }

  private:
    std::shared_ptr<spdlog::logger> previous_;
    std::ostringstream text_;
};

/// The bytes of a file in testdataDir()/`folder`.
inline std::string testdataFile(const std::string& folder, const std::string& name) {
    std::ifstream in(testdataDir() / folder / name, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// gltf/plain.gltf with `edit` applied to its JSON, loaded as the scene's one mesh, beside
/// `files` (the textures the edit refers to).
inline Scene plainGltfWith(const std::function<void(nlohmann::json&)>& edit,
                           std::map<std::string, std::string> files = {}) {
    nlohmann::json gltf = nlohmann::json::parse(testdataFile("gltf", "plain.gltf"));
    edit(gltf);
    files["plain.gltf"] = gltf.dump();
    files["plain.bin"] = testdataFile("gltf", "plain.bin");
    return parseInline(R"({"meshes": [{"file": "plain.gltf"}]})", std::move(files));
}

}  // namespace igi::test
