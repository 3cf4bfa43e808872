#include "output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace candela::record {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(std::string path) : path_(std::move(path)) {
  const fs::path out(path_);
  frames_dir_ = (out / "frames").string();
  manifest_path_ = (out / "manifest.json").string();
  info_path_ = (out / "info.txt").string();
  reserve_path_ = (out / ".manifest-reserve").string();
}

std::string OutputFolder::name() const {
  return fs::absolute(fs::path(path_)).lexically_normal().filename().string();
}

std::string OutputFolder::check_unused() const {
  std::error_code error;
  const bool exists = fs::exists(manifest_path_, error);
  if (error)  // e.g. a parent folder this user may not enter
    return "cannot use " + path_ + ": " + error.message();
  if (exists) return path_ + " already holds a recording (manifest.json); choose another folder";
  return "";
}

std::string OutputFolder::create() const {
  std::error_code error;
  fs::create_directories(frames_dir_, error);
  if (error) return "cannot create " + frames_dir_ + ": " + error.message();
  return "";
}

void write_all(int fd, const std::string& text, const std::string& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      throw OutputError(path + ": write failed: " + std::strerror(err), err);
    }
    done += static_cast<size_t>(n);
  }
}

void write_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    throw OutputError(path + ": cannot write: " + std::strerror(err), err);
  }
  try {
    write_all(fd, text, path);
  } catch (const OutputError&) {
    close(fd);
    unlink(tmp.c_str());
    throw;
  }
  if (close(fd) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    throw OutputError(path + ": write failed: " + std::strerror(err), err);
  }
  if (rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    throw OutputError(path + ": cannot rename into place: " + std::strerror(err), err);
  }
}

bool ManifestReserve::grow(size_t bytes) {
  const int fd = open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  const int r = posix_fallocate(fd, 0, static_cast<off_t>(bytes));
  close(fd);
  return r == 0;
}

void ManifestReserve::release() { unlink(path_.c_str()); }

}  // namespace candela::record
