// The client's folders are layers (client/README.md): a file may include headers of its own
// folder and of the folders below it, never of a folder above, and the GI modes do not include
// one another. This test reads every source file of client/ and fails on an include that breaks
// the order, naming the file, the line and the two folders, so that the layout cannot rot
// one convenient include at a time. Tests and the test helpers in testing/ may include anything.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "util/TestPaths.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

/// Each folder's layer, lowest first; "" is client/ itself (the session and the tile renderer).
/// Folders of one layer may not include each other (the modes are alternatives, not parts).
const std::map<std::string, int>& layers() {
    static const std::map<std::string, int> table = {
        {"materials", 0},   {"tracing", 1},         {"shading", 2},   {"lights", 3},
        {"lighting", 4},    {"integrators", 5},     {"modes/spt", 5}, {"modes/stream", 5},
        {"modes/cache", 5}, {"modes/photonmap", 5}, {"", 6},
    };
    return table;
}

fs::path clientDir() {
    return testing::sourceDir() / "client";
}

/// The folder of a file under client/, as the table names it ("modes/spt", "" for the top).
std::string folderOf(const fs::path& relative) {
    return relative.parent_path().generic_string();
}

bool isTestCode(const fs::path& relative) {
    const std::string name = relative.filename().string();
    return folderOf(relative) == "testing" || name.ends_with("_test.cpp");
}

struct Violation {
    std::string where;  ///< file:line
    std::string text;
};

/// The includes of one file that name a client header (a path with a folder of the table, or
/// a header at the top of client/) and break the order.
std::vector<Violation> violationsIn(const fs::path& relative) {
    static const std::regex include(R"re(^\s*#\s*include\s+"([^"]+)")re");
    std::vector<Violation> found;
    const std::string from = folderOf(relative);
    std::ifstream in(clientDir() / relative);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::smatch match;
        if (!std::regex_search(line, match, include)) continue;
        const fs::path target = match[1].str();
        const std::string where = relative.generic_string() + ":" + std::to_string(number);
        if (!fs::exists(clientDir() / target)) {
            // Found beside the file only: it compiles, but hides its folder from this test.
            if (!from.empty() && fs::exists(clientDir() / from / target))
                found.push_back({where, "include " + target.generic_string() + " as " + from + "/" +
                                            target.generic_string()});
            continue;  // common/, protocol/, net/ or a library
        }
        const std::string to = folderOf(target);
        const auto fromLayer = layers().find(from), toLayer = layers().find(to);
        if (fromLayer == layers().end() || toLayer == layers().end()) {
            found.push_back({where, "folder not in the layer table: " +
                                        (fromLayer == layers().end() ? from : to)});
        } else if (toLayer->second > fromLayer->second ||
                   (toLayer->second == fromLayer->second && to != from)) {
            found.push_back({where, "'" + from + "' (layer " + std::to_string(fromLayer->second) +
                                        ") includes " + target.generic_string() + " of '" + to +
                                        "' (layer " + std::to_string(toLayer->second) + ")"});
        }
    }
    return found;
}

std::vector<fs::path> clientSources() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(clientDir())) {
        const auto ext = entry.path().extension();
        if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp"))
            files.push_back(fs::relative(entry.path(), clientDir()));
    }
    return files;
}

TEST(ClientLayers, EveryFolderIsInTheTable) {
    int sources = 0;
    for (const auto& file : clientSources()) {
        ++sources;
        EXPECT_TRUE(layers().contains(folderOf(file)) || folderOf(file) == "testing")
            << file << ": its folder is not in the layer table of Layers_test.cpp";
    }
    EXPECT_GT(sources, 80) << "the client's sources were not found under " << clientDir();
}

TEST(ClientLayers, NoIncludeRunsUpOrSideways) {
    for (const auto& file : clientSources()) {
        if (isTestCode(file)) continue;
        for (const auto& v : violationsIn(file)) ADD_FAILURE() << v.where << ": " << v.text;
    }
}

}  // namespace
}  // namespace igi
