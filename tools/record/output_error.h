// Why writing the recording failed, as a type: the recorder decides "disk
// full" or "read-only" from errno (or the filesystem's own state), never by
// searching an error message's text.
#pragma once

#include <string>

#include "core/atomic_file.h"

namespace candela::record {

enum class OutputFault {
  kNone,      // nothing failed
  kDiskFull,  // ENOSPC, EDQUOT
  kReadOnly,  // EROFS
  kOther,     // any other failure (permissions, I/O error, ...)
};

// The fault an errno value means (0: kNone).
OutputFault fault_from_errno(int err);

// What the user reads before the reason: "output disk full; ", "output folder
// read-only; ", or "" for the other faults.
const char* fault_prefix(OutputFault fault);

// A write into the output folder failed. what() names the file and says why
// (strerror); error_number() is the errno behind it.
class OutputError : public FileError {
 public:
  using FileError::FileError;
  OutputFault fault() const { return fault_from_errno(error_number()); }
};

// The fault behind any exception: an OutputError's, else kNone (nothing
// says it was the disk).
OutputFault fault_of(const std::exception& e);

}  // namespace candela::record
