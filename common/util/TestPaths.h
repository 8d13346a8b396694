#pragma once
// Where tests find the source tree (scenes, test data, ../shared) and the built executables.
// The build bakes both in (IGI_TEST_SOURCE_DIR, IGI_TEST_BIN_DIR); the environment variables
// IGI_SOURCE_DIR and IGI_BIN_DIR override them.

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>

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

/// A file name of its own in the temporary folder, for a test that writes and reads back a
/// file. ctest runs each test in its own process, several at once: a fixed name let one test
/// read the file another was writing (AlphaDecode failed CI so). The process id and a counter
/// make the name unique; `name` keeps it readable and gives the extension.
inline std::filesystem::path scratchPath(const std::string& name) {
    static std::atomic<int> counter{0};
    return std::filesystem::temp_directory_path() / ("igi-test-" + std::to_string(::getpid()) +
                                                     "-" + std::to_string(counter++) + "-" + name);
}

}  // namespace igi::testing
