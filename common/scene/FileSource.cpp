#include "scene/FileSource.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>
#include <utility>

#include "scene/SceneError.h"

namespace igi {

namespace {

namespace fs = std::filesystem;

// "" and "." both mean the scene file's folder; keys never carry a leading "./".
std::string normalFolder(const std::string& folder) {
    std::string f = fs::path(folder).lexically_normal().generic_string();
    if (f == ".") return "";
    while (!f.empty() && f.back() == '/') f.pop_back();
    return f;
}

std::string folderOf(const std::string& path) {
    return normalFolder(fs::path(path).parent_path().generic_string());
}

}  // namespace

std::string resolveRelative(const std::string& referencingFile, const std::string& name) {
    fs::path joined = fs::path(referencingFile).parent_path() / fs::path(name);
    std::string normal = joined.lexically_normal().generic_string();
    if (normal == ".") return "";
    return normal;
}

DiskFileSource::DiskFileSource(std::filesystem::path root) : root_(std::move(root)) {}

std::string DiskFileSource::read(const std::string& path) {
    auto cached = filesRead_.find(path);
    if (cached != filesRead_.end()) return cached->second;

    std::ifstream in(root_ / path, std::ios::binary);
    std::error_code ec;
    if (!in || fs::is_directory(root_ / path, ec)) {
        throw SceneError::inFile(path, "cannot read file (looked in " +
                                           (root_ / path).lexically_normal().string() + ")");
    }
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) throw SceneError::inFile(path, "error while reading file");
    // Keyed exactly as requested, so that a BundleFileSource answers the same requests.
    return filesRead_.emplace(path, std::move(bytes).str()).first->second;
}

bool DiskFileSource::exists(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(root_ / path, ec);
}

std::vector<std::string> DiskFileSource::list(const std::string& folder) {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(root_ / normalFolder(folder), ec), end; !ec && it != end;
         it.increment(ec)) {
        if (it->is_regular_file(ec)) names.push_back(it->path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

BundleFileSource::BundleFileSource(std::map<std::string, std::string> files)
    : files_(std::move(files)) {}

std::string BundleFileSource::read(const std::string& path) {
    auto it = files_.find(path);
    if (it == files_.end())
        throw SceneError::inFile(path, "cannot read file (not in the scene bundle)");
    return it->second;
}

bool BundleFileSource::exists(const std::string& path) {
    return files_.count(path) > 0;
}

std::vector<std::string> BundleFileSource::list(const std::string& folder) {
    // Only the files the master read are here, which is all a case-insensitive lookup on
    // the master could have picked; std::map keeps them sorted like DiskFileSource::list.
    const std::string wanted = normalFolder(folder);
    std::vector<std::string> names;
    for (const auto& [path, bytes] : files_) {
        if (folderOf(path) == wanted) names.push_back(fs::path(path).filename().string());
    }
    return names;
}

}  // namespace igi
