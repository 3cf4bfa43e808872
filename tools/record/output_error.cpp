#include "output_error.h"

#include <cerrno>

namespace candela::record {

OutputFault fault_from_errno(int err) {
  switch (err) {
    case 0:
      return OutputFault::kNone;
    case ENOSPC:
    case EDQUOT:
      return OutputFault::kDiskFull;
    case EROFS:
      return OutputFault::kReadOnly;
    default:
      return OutputFault::kOther;
  }
}

const char* fault_prefix(OutputFault fault) {
  switch (fault) {
    case OutputFault::kDiskFull:
      return "output disk full; ";
    case OutputFault::kReadOnly:
      return "output folder read-only; ";
    default:
      return "";
  }
}

OutputFault fault_of(const std::exception& e) {
  const auto* oe = dynamic_cast<const OutputError*>(&e);
  return oe ? oe->fault() : OutputFault::kNone;
}

}  // namespace candela::record
