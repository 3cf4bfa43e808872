// The recording's folder: its layout (frames/, info.txt, manifest.json), the
// checks made before a camera is opened, atomic writes that report errno, and
// the room kept on disk for the final manifest.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>

#include "output_error.h"

namespace candela::record {

class OutputFolder {
 public:
  explicit OutputFolder(std::string path);

  const std::string& path() const { return path_; }
  const std::string& frames_dir() const { return frames_dir_; }
  const std::string& manifest_path() const { return manifest_path_; }
  const std::string& info_path() const { return info_path_; }
  const std::string& reserve_path() const { return reserve_path_; }
  // The folder's own name (the default clip name).
  std::string name() const;

  // "" when the folder can take a new recording; otherwise why not (it holds
  // one already, or cannot be looked into).
  std::string check_unused() const;
  // Creates frames/ (and the folder); "" or why it could not.
  std::string create() const;

 private:
  std::string path_, frames_dir_, manifest_path_, info_path_, reserve_path_;
};

// core/atomic_file.h's write_all and write_atomic (path.tmp, then rename),
// their FileError thrown as an OutputError (the same message and errno, and
// its fault()).
void write_all(int fd, const std::string& text, const std::string& path);
void write_atomic(const std::string& path, const std::string& text);

// Room kept for the final manifest (a file of reserved blocks): a full disk
// must not cost the list of frames already written. Grown with the manifest,
// released just before the final write, removed when destroyed.
class ManifestReserve {
 public:
  explicit ManifestReserve(std::string path) : path_(std::move(path)) {}
  ~ManifestReserve() { release(); }
  ManifestReserve(const ManifestReserve&) = delete;
  ManifestReserve& operator=(const ManifestReserve&) = delete;

  // False when the disk cannot give `bytes` any more.
  bool grow(size_t bytes);
  void release();

 private:
  std::string path_;
};

}  // namespace candela::record
