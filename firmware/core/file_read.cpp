#include "core/file_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "core/error.h"

namespace candela {
namespace {

const char* type_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a plain file";
}

// O_NONBLOCK: opening a FIFO with no writer must not wait for one; the fstat
// below then refuses it. O_NOCTTY: a terminal named as a file stays ours.
int open_nonblocking(const std::string& path, std::string* why) {
  int fd;
  do {
    fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) *why = std::string("cannot open: ") + std::strerror(errno);
  return fd;
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw ConfigError(path, "", why);
}

std::string too_big(uint64_t bytes, FileKind kind) {
  return format_bytes(bytes) + ", larger than the " + format_bytes(max_file_bytes(kind)) +
         " limit for " + file_kind_name(kind);
}

}  // namespace

uint64_t max_file_bytes(FileKind kind) {
  switch (kind) {
    case FileKind::kScene:
      return uint64_t{1} << 20;  // the largest shipped scene is a few KB
    case FileKind::kModel:
      return uint64_t{256} << 20;  // the built-in model is 0.7 MB
    case FileKind::kImage:
      return uint64_t{64} << 20;
    case FileKind::kNoiseTable:
      return uint64_t{256} << 10;  // 65536 samples: 128 KB
  }
  return 0;
}

const char* file_kind_name(FileKind kind) {
  switch (kind) {
    case FileKind::kScene:
      return "a scene";
    case FileKind::kModel:
      return "a model";
    case FileKind::kImage:
      return "a PNG image";
    case FileKind::kNoiseTable:
      return "a noise table";
  }
  return "a file";
}

std::string format_bytes(uint64_t b) {
  char buf[48];
  if (b < 1024)
    std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(b));
  else if (b < (uint64_t{1} << 20))
    std::snprintf(buf, sizeof buf, "%.1f KB", static_cast<double>(b) / 1024);
  else if (b < (uint64_t{1} << 30))
    std::snprintf(buf, sizeof buf, "%.1f MB", static_cast<double>(b) / (1 << 20));
  else
    std::snprintf(buf, sizeof buf, "%.1f GB", static_cast<double>(b) / (1 << 30));
  std::string s = buf;
  const auto dot = s.find(".0 ");  // "64.0 MB" -> "64 MB"
  if (dot != std::string::npos) s.erase(dot, 2);
  return s;
}

BoundedFile BoundedFile::open(const std::string& path, FileKind kind) {
  std::string why;
  const int fd = open_nonblocking(path, &why);
  if (fd < 0) fail(path, why);
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    why = std::string("cannot stat: ") + std::strerror(errno);
    ::close(fd);
    fail(path, why);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    fail(path, std::string("not a regular file (") + type_of(st.st_mode) + ")");
  }
  const auto size = static_cast<uint64_t>(st.st_size);
  if (size > max_file_bytes(kind)) {
    ::close(fd);
    fail(path, too_big(size, kind));
  }
  // Regular files never block; clear the flag so reads behave as usual.
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return BoundedFile(fd, size, path, kind);
}

BoundedFile::BoundedFile(BoundedFile&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)), size_(o.size_), path_(std::move(o.path_)), kind_(o.kind_) {}

BoundedFile& BoundedFile::operator=(BoundedFile&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
    size_ = o.size_;
    path_ = std::move(o.path_);
    kind_ = o.kind_;
  }
  return *this;
}

BoundedFile::~BoundedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void BoundedFile::read_exactly(void* dst) {
  auto* p = static_cast<uint8_t*>(dst);
  uint64_t got = 0;
  while (got < size_) {
    const ssize_t r = ::read(fd_, p + got, size_ - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) fail(path_, std::string("cannot read: ") + std::strerror(errno));
    if (r == 0)
      fail(path_, "the file shrank while it was read (" + std::to_string(got) + " of " +
                      std::to_string(size_) + " bytes); is it being rewritten?");
    got += static_cast<uint64_t>(r);
  }
  uint8_t extra;
  ssize_t r;
  while ((r = ::read(fd_, &extra, 1)) < 0 && errno == EINTR) {
  }
  if (r > 0) fail(path_, "the file grew while it was read; is it being rewritten?");
}

std::string BoundedFile::read_all() {
  const uint64_t limit = max_file_bytes(kind_);
  std::string out;
  out.reserve(static_cast<size_t>(size_));
  char buf[65536];
  for (;;) {
    const ssize_t r = ::read(fd_, buf, sizeof buf);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) fail(path_, std::string("cannot read: ") + std::strerror(errno));
    if (r == 0) break;
    if (out.size() + static_cast<uint64_t>(r) > limit)
      fail(path_, "more than the " + format_bytes(limit) + " limit for " + file_kind_name(kind_));
    out.append(buf, static_cast<size_t>(r));
  }
  return out;
}

std::string read_bounded_file(const std::string& path, FileKind kind) {
  return BoundedFile::open(path, kind).read_all();
}

std::string regular_file_problem(const std::string& path) {
  std::string why;
  const int fd = open_nonblocking(path, &why);
  if (fd < 0) return why;
  struct stat st {};
  if (fstat(fd, &st) != 0)
    why = std::string("cannot stat: ") + std::strerror(errno);
  else if (!S_ISREG(st.st_mode))
    why = std::string("not a regular file (") + type_of(st.st_mode) + ")";
  ::close(fd);
  return why;
}

}  // namespace candela
