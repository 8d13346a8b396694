#include "OutputCheck.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const fs::path& path, const std::string& flag = "--output") {
    try {
        checkImageOutput(path, flag);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

// Issue 40: --output out.jpg or /proc/x.png failed only after every frame was rendered.
TEST(OutputCheck, RefusesTypesAndFoldersBeforeTheRun) {
    EXPECT_CONTAINS(errorOf("out.jpg"), "--output out.jpg: unsupported image type '.jpg'");
    EXPECT_CONTAINS(errorOf("noextension"), "unsupported image type ''");
    EXPECT_CONTAINS(errorOf("/proc/x.png"),
                    "--output /proc/x.png: cannot write in the folder /proc");
    EXPECT_CONTAINS(errorOf("/proc/self/new/x.exr", "--output-sequence"),
                    "--output-sequence /proc/self/new/x.exr: cannot make the folder");
    const fs::path dir =
        fs::temp_directory_path() / ("igi-outputcheck-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "a.png");
    EXPECT_CONTAINS(errorOf(dir / "a.png"), "is a folder, not a file");
    fs::remove_all(dir);
}

// --error-output holds relMSE values, linear and mostly far below one: an .exr only.
TEST(OutputCheck, ErrorOutputMustBeAnExrInAWritableFolder) {
    const auto errorOfErrorOutput = [](const fs::path& path) -> std::string {
        try {
            checkErrorOutput(path);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_CONTAINS(errorOfErrorOutput("error.png"), "--error-output error.png: must be an .exr");
    EXPECT_CONTAINS(errorOfErrorOutput("/proc/error.exr"),
                    "--error-output /proc/error.exr: cannot write in the folder /proc");
    EXPECT_EQ(errorOfErrorOutput(fs::temp_directory_path() / "error.exr"), "");
}

TEST(OutputCheck, MakesMissingFoldersAndLeavesNothingBehind) {
    const fs::path dir =
        fs::temp_directory_path() / ("igi-outputcheck-" + std::to_string(getpid()));
    fs::remove_all(dir);
    EXPECT_EQ(errorOf(dir / "sub" / "image.png"), "");
    EXPECT_TRUE(fs::is_directory(dir / "sub"));
    EXPECT_TRUE(fs::is_empty(dir / "sub")) << "the probe file stays";
    EXPECT_NO_THROW(checkWritableFolder(dir / "stats.json", "--stats-json"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
