#include "output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>

#include "core/atomic_file.h"

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

namespace {
template <class Write>
void as_output_error(const Write& write) {
  try {
    write();
  } catch (const FileError& e) {
    throw OutputError(e.what(), e.error_number());
  }
}
}  // namespace

void write_all(int fd, const std::string& text, const std::string& path) {
  as_output_error([&] { candela::write_all(fd, text, path); });
}

void write_atomic(const std::string& path, const std::string& text) {
  as_output_error([&] { candela::write_atomic(path, text); });
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
