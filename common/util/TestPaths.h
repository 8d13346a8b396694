#pragma once
// Where tests find the source tree (scenes, test data, ../shared) and the built executables.
// The build bakes both in (IGI_TEST_SOURCE_DIR, IGI_TEST_BIN_DIR); the environment variables
// IGI_SOURCE_DIR and IGI_BIN_DIR override them.

#include <cstdlib>
#include <filesystem>

namespace igi::testing {

inline std::filesystem::path sourceDir() {
    if (const char* dir = std::getenv("IGI_SOURCE_DIR")) return dir;
#ifdef IGI_TEST_SOURCE_DIR
    return IGI_TEST_SOURCE_DIR;
#else
    return ".";
#endif
}

inline std::filesystem::path binDir() {
    if (const char* dir = std::getenv("IGI_BIN_DIR")) return dir;
#ifdef IGI_TEST_BIN_DIR
    return IGI_TEST_BIN_DIR;
#else
    return "build/bin";
#endif
}

/// The public test scenes, next to the project: ../shared/scenes.
inline std::filesystem::path sharedScenesDir() {
    return (sourceDir() / ".." / "shared" / "scenes").lexically_normal();
}

}  // namespace igi::testing
