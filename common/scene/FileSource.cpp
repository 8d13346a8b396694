#include "scene/FileSource.h"

#include <algorithm>
#include <fstream>
#include <system_error>
#include <utility>
#include <vector>

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

const std::string kAllowHint = "pass --allow-outside-paths to allow it";

// A path for messages, NUL bytes shown as \0.
std::string printablePath(const std::string& path) {
    std::string out;
    for (char c : path) out += c == '\0' ? std::string("\\0") : std::string(1, c);
    return out;
}

std::string tooLarge(std::uintmax_t size, std::uint64_t maxBytes) {
    return "file is " + std::to_string(size) + " bytes, over the limit of " +
           std::to_string(maxBytes) + " bytes";
}

}  // namespace

std::string resolveRelative(const std::string& referencingFile, const std::string& name) {
    fs::path joined = fs::path(referencingFile).parent_path() / fs::path(name);
    std::string normal = joined.lexically_normal().generic_string();
    if (normal == ".") return "";
    return normal;
}

DiskFileSource::DiskFileSource(std::filesystem::path root, SceneLoadOptions options)
    : root_(std::move(root)),
      options_(std::move(options)),
      totalBytes_(options_.limits.maxTotalBytes, "bytes", "read per scene") {
    std::error_code ec;
    canonicalRoot_ = fs::weakly_canonical(root_.empty() ? fs::path(".") : root_, ec);
    if (ec) canonicalRoot_ = fs::absolute(root_, ec).lexically_normal();
}

void DiskFileSource::checkPath(const std::string& path) {
    // Never allowed: the OS would silently cut the name at the NUL.
    if (path.find('\0') != std::string::npos)
        throw SceneError::inFile(printablePath(path), "path contains a NUL byte");
    if (options_.allowOutsidePaths) return;
    const fs::path p(path);
    const fs::path normal = p.lexically_normal();
    if (p.has_root_path() || (!normal.empty() && *normal.begin() == "..")) {
        throw SceneError::inFile(path,
                                 "path '" + path + "' leaves the scene's folder; " + kAllowHint);
    }
    // Resolved as the OS will open it: symbolic links first, then "..".
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(root_ / p, ec);
    if (ec) throw SceneError::inFile(path, "cannot resolve path: " + ec.message());
    const fs::path relative = real.lexically_relative(canonicalRoot_);
    if (relative.empty() || *relative.begin() == "..") {
        throw SceneError::inFile(path, "path '" + path + "' leads out of the scene's folder (to '" +
                                           real.string() + "', through a symbolic link); " +
                                           kAllowHint);
    }
}

std::string DiskFileSource::read(const std::string& path) {
    auto cached = filesRead_.find(path);
    if (cached != filesRead_.end()) return cached->second;

    checkPath(path);
    const fs::path file = root_ / path;
    // Refused before reading when the size is known; readRegularFile reports other problems.
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (!ec && !totalBytes_.fits(size)) throw SceneError::inFile(path, totalBytes_.exceeded(size));
    std::string bytes = readRegularFile(file, options_.limits.maxFileBytes, path);
    if (!totalBytes_.fits(bytes.size()))
        throw SceneError::inFile(path, totalBytes_.exceeded(bytes.size()));
    totalBytes_.add(bytes.size());
    // Keyed exactly as requested, so that a BundleFileSource answers the same requests.
    return filesRead_.emplace(path, std::move(bytes)).first->second;
}

bool DiskFileSource::exists(const std::string& path) {
    checkPath(path);
    std::error_code ec;
    return fs::is_regular_file(root_ / path, ec);
}

std::vector<std::string> DiskFileSource::list(const std::string& folder) {
    checkPath(normalFolder(folder));
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(root_ / normalFolder(folder), ec), end; !ec && it != end;
         it.increment(ec)) {
        if (it->is_regular_file(ec)) names.push_back(it->path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::string readRegularFile(const std::filesystem::path& file, std::uint64_t maxBytes,
                            const std::string& name) {
    const std::string where = " (looked in " + file.lexically_normal().string() + ")";
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (ec || !fs::exists(status)) throw SceneError::inFile(name, "cannot read file" + where);
    // A device or a FIFO (/dev/zero) would never end.
    if (!fs::is_regular_file(status))
        throw SceneError::inFile(name, "cannot read file: not a regular file" + where);
    const std::uintmax_t size = fs::file_size(file, ec);
    if (!ec && size > maxBytes) throw SceneError::inFile(name, tooLarge(size, maxBytes));
    std::ifstream in(file, std::ios::binary);
    if (!in) throw SceneError::inFile(name, "cannot read file" + where);
    std::string bytes;
    bytes.reserve(ec ? 0 : size);
    // In chunks, counting: the file may have grown since it was measured.
    std::vector<char> chunk(1 << 16);
    while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got > maxBytes - bytes.size())
            throw SceneError::inFile(name, tooLarge(bytes.size() + got, maxBytes));
        bytes.append(chunk.data(), got);
    }
    if (in.bad()) throw SceneError::inFile(name, "error while reading file");
    return bytes;
}

void checkBundlePath(const std::string& path) {
    if (path.empty()) throw SceneError::inFile("scene bundle", "a file has an empty name");
    if (path.find('\0') != std::string::npos) {
        throw SceneError::inFile(printablePath(path),
                                 "file name in the scene bundle contains a NUL byte");
    }
    if (fs::path(path).has_root_path()) {
        throw SceneError::inFile(path,
                                 "absolute file name: a scene bundle holds paths relative to the "
                                 "scene file (clients never read their own disk)");
    }
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

std::string DiskFileSource::displayName(const std::string& path) const {
    if (std::filesystem::path(path).is_absolute()) return path;
    return (root_ / path).lexically_normal().string();
}

}  // namespace igi
