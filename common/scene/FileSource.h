#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "scene/SceneLimits.h"

namespace igi {

/// Where a scene's files come from. Paths are relative to the scene file's folder and
/// lexically normal ("meshes/box.obj", "../shared/scenes/x.obj"); the master reads them from
/// disk, a client from the bundle the master sent, so both parse the same bytes.
class FileSource {
  public:
    virtual ~FileSource() = default;
    /// The file's bytes; throws SceneError naming the path when it cannot be read.
    virtual std::string read(const std::string& path) = 0;
    virtual bool exists(const std::string& path) = 0;
    /// Names of the files in a folder ("" is the scene file's folder), for the
    /// case-insensitive lookup of textures.
    virtual std::vector<std::string> list(const std::string& folder) = 0;
    /// Throws SceneError naming `path` when this source refuses it whatever the file holds (a
    /// DiskFileSource refuses paths that leave the scene's folder). read, exists and list
    /// check it too; the loaders call it first where they can name the line or JSON path of
    /// the reference.
    virtual void checkPath(const std::string& path) { (void)path; }
    /// `path` as a user would find the file, for warnings (errors are renamed where they are
    /// caught, warnings are written at once).
    virtual std::string displayName(const std::string& path) const { return path; }
};

/// Reads files under a root folder and remembers every file it read, so that the master can
/// ship exactly those bytes to the clients. Unless options.allowOutsidePaths, it refuses
/// (SceneError) a path that is absolute, starts with ".." once lexically normal, or resolves
/// (symbolic links followed) to a place outside the root. It reads regular files only, each
/// at most options.limits.maxFileBytes and all together at most maxTotalBytes.
class DiskFileSource : public FileSource {
  public:
    explicit DiskFileSource(std::filesystem::path root, SceneLoadOptions options = {});
    std::string read(const std::string& path) override;
    bool exists(const std::string& path) override;
    std::vector<std::string> list(const std::string& folder) override;
    void checkPath(const std::string& path) override;
    /// Relative to the working directory, as the user named the scene file.
    std::string displayName(const std::string& path) const override;
    const std::map<std::string, std::string>& filesRead() const { return filesRead_; }

  private:
    std::filesystem::path root_;
    std::filesystem::path canonicalRoot_;
    SceneLoadOptions options_;
    Budget totalBytes_;
    std::map<std::string, std::string> filesRead_;
};

/// Serves files from memory (what a client received).
class BundleFileSource : public FileSource {
  public:
    explicit BundleFileSource(std::map<std::string, std::string> files);
    std::string read(const std::string& path) override;
    bool exists(const std::string& path) override;
    std::vector<std::string> list(const std::string& folder) override;

  private:
    std::map<std::string, std::string> files_;
};

/// The bytes of a regular file of at most `maxBytes` bytes; throws SceneError naming `name`
/// when it is not a regular file, cannot be read, or is larger (checked before reading, and
/// again while reading in case it grows).
std::string readRegularFile(const std::filesystem::path& file, std::uint64_t maxBytes,
                            const std::string& name);

/// Throws SceneError when a bundle's file name is one a client must not accept: empty,
/// absolute, or containing a NUL byte.
void checkBundlePath(const std::string& path);

/// Joins a relative path to the folder of another and normalizes it lexically
/// ("a/b.obj" + "c.mtl" -> "a/c.mtl"; "../x/y.obj" + "../t.png" -> "../t.png").
std::string resolveRelative(const std::string& referencingFile, const std::string& name);

}  // namespace igi
