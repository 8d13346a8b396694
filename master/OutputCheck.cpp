#include "OutputCheck.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace igi {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(const std::string& flag, const fs::path& path, const std::string& why) {
    throw std::invalid_argument(flag + " " + path.string() + ": " + why);
}

// The only sure test that a folder takes a new file is to make one: permission bits do not
// tell (root passes them, and /proc or a read-only mount refuse root).
void probeFolder(const fs::path& folder, const std::string& flag, const fs::path& path) {
    const fs::path probe = folder / (".igi-write-check-" + std::to_string(getpid()));
    const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0)
        refuse(flag, path,
               "cannot write in the folder " + folder.string() + ": " + std::strerror(errno));
    close(fd);
    unlink(probe.c_str());
}

}  // namespace

void checkWritableFolder(const fs::path& path, const std::string& flag) {
    if (path.empty()) refuse(flag, path, "no file name");
    std::error_code ec;
    if (fs::is_directory(path, ec)) refuse(flag, path, "is a folder, not a file");
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    fs::create_directories(folder, ec);
    if (ec) refuse(flag, path, "cannot make the folder " + folder.string() + ": " + ec.message());
    probeFolder(folder, flag, path);
}

void checkImageOutput(const fs::path& path, const std::string& flag) {
    const std::string ext = path.extension().string();
    if (ext != ".png" && ext != ".exr")
        refuse(flag, path,
               "unsupported image type '" + ext + "' (.png tone-mapped, or .exr linear)");
    checkWritableFolder(path, flag);
}

void checkErrorOutput(const fs::path& path) {
    if (path.extension() != ".exr")
        refuse("--error-output", path,
               "must be an .exr (linear relMSE values; a tone-mapped .png would show them black)");
    checkWritableFolder(path, "--error-output");
}

}  // namespace igi
