#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

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
};

/// Reads files under a root folder and remembers every file it read, so that the master can
/// ship exactly those bytes to the clients.
class DiskFileSource : public FileSource {
  public:
    explicit DiskFileSource(std::filesystem::path root);
    std::string read(const std::string& path) override;
    bool exists(const std::string& path) override;
    std::vector<std::string> list(const std::string& folder) override;
    const std::map<std::string, std::string>& filesRead() const { return filesRead_; }

  private:
    std::filesystem::path root_;
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

/// Joins a relative path to the folder of another and normalizes it lexically
/// ("a/b.obj" + "c.mtl" -> "a/c.mtl"; "../x/y.obj" + "../t.png" -> "../t.png").
std::string resolveRelative(const std::string& referencingFile, const std::string& name);

}  // namespace igi
