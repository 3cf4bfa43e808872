// Files written whole or not at all: into PATH.tmp, then renamed over PATH,
// so a reader (or a crash) never sees half a file. Every file the runtime
// and the tools write this way goes through here.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

#include "core/error.h"

namespace candela {

// A file the OS would not write: what() names the file and says why
// (strerror); error_number() is the errno behind it, so a caller can tell a
// full disk from the rest without reading the message.
class FileError : public RuntimeError {
 public:
  FileError(const std::string& message, int error_number)
      : RuntimeError(message), error_number_(error_number) {}
  int error_number() const { return error_number_; }

 private:
  int error_number_;
};

// Writes all of `bytes` to the open file `fd` (retrying short writes and
// EINTR); throws FileError naming `path` ("<path>: write failed: <strerror>").
void write_all(int fd, std::string_view bytes, const std::string& path);

// Writes `bytes` to `path` atomically. Throws FileError naming `path` and
// carrying errno ("cannot write", "write failed", "cannot rename into
// place"); leaves no .tmp behind.
void write_atomic(const std::string& path, std::string_view bytes);

// The same for a writer that streams (libpng): `write` gets PATH.tmp open
// for writing and may throw to give up (the .tmp is removed, the exception
// passed on); a failed write or flush throws FileError as above.
void write_atomic(const std::string& path, const std::function<void(std::FILE*)>& write);

}  // namespace candela
