// The one way Candela reads a file it was told about (scene, model, PNG still
// or profile, noise/gust table): regular files only, opened non-blocking (a
// FIFO cannot hang start-up or --check), and never more than the limit for
// its kind (checked with fstat before reading, and again while reading, since
// /proc-like files report size 0). Errors are ConfigError(path, "", why):
//   "not a regular file (a FIFO)", "1.2 GB, larger than the 64 MB limit for a
//   scene", "cannot open: Too many levels of symbolic links".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace candela {

enum class FileKind { kScene, kModel, kImage, kNoiseTable };

// The size limit for a kind, and its name in messages ("a model").
uint64_t max_file_bytes(FileKind kind);
const char* file_kind_name(FileKind kind);
// 1536 -> "1.5 KB", 1288490189 -> "1.2 GB" (binary units).
std::string format_bytes(uint64_t bytes);

// An open, regular file no larger than its kind allows. Move-only; closes on destruction.
class BoundedFile {
 public:
  static BoundedFile open(const std::string& path, FileKind kind);
  BoundedFile(BoundedFile&& o) noexcept;
  BoundedFile& operator=(BoundedFile&& o) noexcept;
  BoundedFile(const BoundedFile&) = delete;
  BoundedFile& operator=(const BoundedFile&) = delete;
  ~BoundedFile();

  int fd() const { return fd_; }
  uint64_t size() const { return size_; }  // as fstat saw it
  // Reads the whole file into dst (capacity: size() bytes). Throws if the file
  // shrank or grew since open() (it is being rewritten).
  void read_exactly(void* dst);
  // Reads to end of file (for files whose fstat size cannot be trusted), at most the limit.
  std::string read_all();

 private:
  BoundedFile(int fd, uint64_t size, std::string path, FileKind kind)
      : fd_(fd), size_(size), path_(std::move(path)), kind_(kind) {}
  int fd_ = -1;
  uint64_t size_ = 0;
  std::string path_;
  FileKind kind_ = FileKind::kScene;
};

// The whole file as bytes, within its kind's limit.
std::string read_bounded_file(const std::string& path, FileKind kind);

// Empty if `path` names a readable regular file; otherwise why not ("not a
// regular file (a directory)", "cannot open: No such file or directory").
std::string regular_file_problem(const std::string& path);

}  // namespace candela
