#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace candela {
namespace {
[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw FileError(path + ": " + what + ": " + std::strerror(err), err);
}

void rename_into_place(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    fail(path, "cannot rename into place", err);
  }
}
}  // namespace

void write_all(int fd, std::string_view bytes, const std::string& path) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path, "write failed", n < 0 ? errno : ENOSPC);
    done += static_cast<size_t>(n);
  }
}

void write_atomic(const std::string& path, std::string_view bytes) {
  const std::string tmp = path + ".tmp";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "cannot write", errno);
  try {
    write_all(fd, bytes, path);
  } catch (const FileError&) {
    close(fd);
    unlink(tmp.c_str());
    throw;
  }
  if (close(fd) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    fail(path, "write failed", err);
  }
  rename_into_place(tmp, path);
}

void write_atomic(const std::string& path, const std::function<void(std::FILE*)>& write) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(path, "cannot write", errno);
  try {
    write(f);
  } catch (...) {
    std::fclose(f);
    unlink(tmp.c_str());
    throw;
  }
  int err = 0;
  if (std::fflush(f) != 0 || std::ferror(f)) err = errno ? errno : EIO;
  if (std::fclose(f) != 0 && !err) err = errno ? errno : EIO;
  if (err) {
    unlink(tmp.c_str());
    fail(path, "write failed", err);
  }
  rename_into_place(tmp, path);
}

}  // namespace candela
