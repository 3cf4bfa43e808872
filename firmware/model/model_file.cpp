#include "model/model_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/file_read.h"
#include "core/json_parse.h"

namespace candela::model {

size_t dtype_size(DType t) {
  switch (t) {
    case DType::kU8:
      return 1;
    case DType::kU16:
      return 2;
    case DType::kI32:
    case DType::kF32:
      return 4;
  }
  return 1;
}

const char* dtype_name(DType t) {
  switch (t) {
    case DType::kU8:
      return "U8";
    case DType::kU16:
      return "U16";
    case DType::kI32:
      return "I32";
    case DType::kF32:
      return "F32";
  }
  return "?";
}

const char* to_string(ModelError::Kind k) {
  switch (k) {
    case ModelError::Kind::kIo:
      return "io";
    case ModelError::Kind::kTruncated:
      return "truncated";
    case ModelError::Kind::kHeader:
      return "header";
    case ModelError::Kind::kVersion:
      return "version";
    case ModelError::Kind::kChecksum:
      return "checksum";
    case ModelError::Kind::kInconsistent:
      return "inconsistent";
  }
  return "?";
}

// A private, page-aligned copy of a file (anonymous memory), an owned buffer
// or bytes the program holds for its whole run (neither `map` nor `owned`).
struct ModelFile::Storage {
  const uint8_t* data = nullptr;
  size_t size = 0;
  void* map = nullptr;
  std::vector<uint8_t> owned;
  Storage() = default;
  Storage(const Storage&) = delete;
  Storage& operator=(const Storage&) = delete;
  ~Storage() {
    if (map) munmap(map, size);
  }
};

size_t ModelFile::file_size() const { return storage_ ? storage_->size : 0; }

size_t ModelFile::give_back_pages(const uint8_t* data, size_t bytes) const {
  // Only bytes that live in the binary (read-only, file-backed): in anonymous
  // or heap memory MADV_DONTNEED would lose them.
  if (!storage_ || storage_->map || !storage_->owned.empty() || bytes == 0) return 0;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data);
  const uintptr_t lo = reinterpret_cast<uintptr_t>(storage_->data);
  if (begin < lo || begin + bytes > lo + storage_->size) return 0;  // not this file's bytes
  const long page_size = sysconf(_SC_PAGESIZE);
  if (page_size <= 0) return 0;
  const uintptr_t page = static_cast<uintptr_t>(page_size);
  const uintptr_t first = (begin + page - 1) / page * page, end = (begin + bytes) / page * page;
  if (end <= first) return 0;
  if (madvise(reinterpret_cast<void*>(first), end - first, MADV_DONTNEED) != 0) return 0;
  return end - first;
}

namespace {

using Kind = ModelError::Kind;

bool parse_dtype(const std::string& s, DType* out) {
  static const std::pair<const char*, DType> names[] = {
      {"U8", DType::kU8}, {"U16", DType::kU16}, {"I32", DType::kI32}, {"F32", DType::kF32}};
  for (const auto& [n, t] : names) {
    if (s == n) {
      *out = t;
      return true;
    }
  }
  return false;
}

std::string hex32(uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

}  // namespace

uint32_t model_checksum(const nlohmann::json& header_without_checksum, const uint8_t* data,
                        size_t data_bytes) {
  const std::string canon = header_without_checksum.dump();
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32_z(crc, reinterpret_cast<const Bytef*>(canon.data()), canon.size());
  crc = crc32_z(crc, data, data_bytes);
  return static_cast<uint32_t>(crc);
}

ModelFile ModelFile::open(const std::string& path) {
  auto storage = std::make_shared<Storage>();
  // Regular files only, opened non-blocking, within the size limit for a
  // model (core/file_read.h), checked before anything is allocated or read.
  auto bounded = [&]() {
    try {
      return BoundedFile::open(path, FileKind::kModel);
    } catch (const ConfigError& e) {
      throw ModelError(Kind::kIo, path, "", e.expected());
    }
  }();
  storage->size = static_cast<size_t>(bounded.size());
  // Read once into private, page-aligned memory rather than mapping the file:
  // a mapped file that someone overwrites in place (`cp new.cmodel` over it
  // while candela runs) would kill the display with SIGBUS on the next touch
  // of a truncated page. A loaded model never depends on its file again.
  if (storage->size > 0) {
    void* m =
        mmap(nullptr, storage->size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED)
      throw ModelError(
          Kind::kIo, path, "",
          "cannot allocate " + std::to_string(storage->size) + " bytes: " + std::strerror(errno));
    storage->map = m;
    storage->data = static_cast<const uint8_t*>(m);
    try {
      bounded.read_exactly(m);
    } catch (const ConfigError& e) {
      throw ModelError(Kind::kIo, path, "", e.expected());
    }
    mprotect(m, storage->size, PROT_READ);  // read-only from here, as a mapping was
  }
  return parse(std::move(storage), path);
}

ModelFile ModelFile::from_static(std::string_view bytes, const std::string& name) {
  auto storage = std::make_shared<Storage>();
  storage->data = reinterpret_cast<const uint8_t*>(bytes.data());
  storage->size = bytes.size();
  return parse(std::move(storage), name);
}

ModelFile ModelFile::from_bytes(std::vector<uint8_t> bytes, const std::string& name) {
  auto storage = std::make_shared<Storage>();
  storage->owned = std::move(bytes);
  storage->data = storage->owned.data();
  storage->size = storage->owned.size();
  return parse(std::move(storage), name);
}

ModelFile ModelFile::parse(std::shared_ptr<const Storage> storage, const std::string& name) {
  ModelFile f;
  f.path_ = name;
  const uint8_t* p = storage->data;
  const size_t size = storage->size;
  if (size < 8)
    throw ModelError(Kind::kTruncated, name, "header length",
                     "file has " + std::to_string(size) + " bytes, fewer than the 8-byte length");
  uint64_t hlen = 0;
  for (int i = 7; i >= 0; --i) hlen = (hlen << 8) | p[i];
  if (hlen > kMaxHeaderBytes)
    throw ModelError(Kind::kHeader, name, "header length",
                     "declares " + std::to_string(hlen) + " bytes, more than any model header");
  if (hlen > size - 8)
    throw ModelError(Kind::kTruncated, name, "header",
                     "declares " + std::to_string(hlen) + " header bytes but only " +
                         std::to_string(size - 8) + " follow");
  // Nesting bounded before the tree is built: the checksum below re-serialises
  // the header, recursively (core/json_parse.h).
  std::string json_error;
  std::optional<nlohmann::json> parsed = try_parse_json(
      std::string_view(reinterpret_cast<const char*>(p + 8), static_cast<size_t>(hlen)),
      &json_error);
  if (!parsed) throw ModelError(Kind::kHeader, name, "header", json_error);
  nlohmann::json header = std::move(*parsed);
  if (!header.is_object())
    throw ModelError(Kind::kHeader, name, "header", "expected a JSON object");
  auto meta_it = header.find("__metadata__");
  if (meta_it == header.end() || !meta_it->is_object())
    throw ModelError(Kind::kHeader, name, "__metadata__", "missing (not a Candela model file)");
  nlohmann::json& meta = *meta_it;
  auto fmt = meta.find("format");
  if (fmt == meta.end() || !fmt->is_string() || fmt->get<std::string>() != kFormatName)
    throw ModelError(Kind::kHeader, name, "__metadata__.format",
                     "expected \"candela-model\" (not a Candela model file)");
  auto ver = meta.find("version");
  if (ver == meta.end() || !ver->is_number_integer())
    throw ModelError(Kind::kHeader, name, "__metadata__.version", "expected an integer");
  f.version_ = ver->get<int>();
  if (f.version_ != kFormatVersion)
    throw ModelError(Kind::kVersion, name, "__metadata__.version",
                     "file has format version " + std::to_string(f.version_) +
                         ", this reader understands version " + std::to_string(kFormatVersion));
  auto db = meta.find("data_bytes");
  if (db == meta.end() || !db->is_number_unsigned())
    throw ModelError(Kind::kHeader, name, "__metadata__.data_bytes",
                     "expected the data section's size");
  const uint64_t data_bytes = db->get<uint64_t>();
  const size_t data_start = 8 + hlen;
  if (data_start % kAlignment != 0)
    throw ModelError(
        Kind::kInconsistent, name, "header length",
        "data section must start on a " + std::to_string(kAlignment) + "-byte boundary");
  if (data_bytes > size - data_start)
    throw ModelError(Kind::kTruncated, name, "data",
                     "declares " + std::to_string(data_bytes) + " data bytes but only " +
                         std::to_string(size - data_start) + " are present");
  if (data_bytes < size - data_start)
    throw ModelError(Kind::kInconsistent, name, "data",
                     std::to_string(size - data_start - data_bytes) +
                         " unexpected bytes after the data section");
  auto ck = meta.find("checksum");
  if (ck == meta.end() || !ck->is_string())
    throw ModelError(Kind::kHeader, name, "__metadata__.checksum", "expected \"crc32:xxxxxxxx\"");
  const std::string ck_text = ck->get<std::string>();
  meta.erase("checksum");
  const uint8_t* data = p + data_start;
  const uint32_t actual = model_checksum(header, data, data_bytes);
  if (ck_text != "crc32:" + hex32(actual))
    throw ModelError(
        Kind::kChecksum, name, "__metadata__.checksum",
        "stored " + ck_text + " but contents give crc32:" + hex32(actual) + " (file corrupt)");
  f.checksum_ = actual;

  // The tensor table: well-formed, inside the data, aligned, not overlapping.
  std::vector<std::pair<uint64_t, uint64_t>> ranges;
  for (auto it = header.begin(); it != header.end(); ++it) {
    if (it.key() == "__metadata__") continue;
    const std::string field = "tensor " + it.key();
    const auto& e = it.value();
    auto bad = [&](const std::string& what) {
      throw ModelError(Kind::kInconsistent, name, field, what);
    };
    if (!e.is_object()) bad("expected {dtype, shape, data_offsets}");
    Tensor t;
    t.name = it.key();
    auto dt = e.find("dtype");
    if (dt == e.end() || !dt->is_string() || !parse_dtype(dt->get<std::string>(), &t.dtype))
      bad("dtype must be one of U8, U16, I32, F32");
    auto sh = e.find("shape");
    if (sh == e.end() || !sh->is_array() || sh->size() > 8)
      bad("shape must be an array (rank <= 8)");
    uint64_t count = 1;
    for (const auto& d : *sh) {
      if (!d.is_number_unsigned()) bad("shape entries must be non-negative integers");
      uint64_t v = d.get<uint64_t>();
      if (v > (uint64_t{1} << 40) || (v != 0 && count > (uint64_t{1} << 40) / v))
        bad("shape is implausibly large");
      count *= v;
      t.shape.push_back(static_cast<int64_t>(v));
    }
    auto off = e.find("data_offsets");
    if (off == e.end() || !off->is_array() || off->size() != 2 || !(*off)[0].is_number_unsigned() ||
        !(*off)[1].is_number_unsigned())
      bad("data_offsets must be [begin, end]");
    uint64_t b = (*off)[0].get<uint64_t>(), en = (*off)[1].get<uint64_t>();
    if (en < b || en > data_bytes) bad("data_offsets lie outside the data section");
    if (en - b != count * dtype_size(t.dtype))
      bad("holds " + std::to_string(en - b) + " bytes but dtype x shape needs " +
          std::to_string(count * dtype_size(t.dtype)));
    if ((data_start + b) % kAlignment != 0) bad("data is not 64-byte aligned");
    t.data = data + b;
    t.bytes = static_cast<size_t>(en - b);
    ranges.emplace_back(b, en);
    f.tensors_.push_back(std::move(t));
  }
  std::sort(ranges.begin(), ranges.end());
  for (size_t i = 1; i < ranges.size(); ++i)
    if (ranges[i].first < ranges[i - 1].second)
      throw ModelError(Kind::kInconsistent, name, "data_offsets", "two tensors overlap");
  auto mi = meta.find("model");
  if (mi == meta.end() || !mi->is_object())
    throw ModelError(Kind::kInconsistent, name, "__metadata__.model", "expected an object");
  f.info_ = std::move(*mi);
  f.header_bytes_ = data_start;
  f.storage_ = std::move(storage);
  return f;
}

const Tensor* ModelFile::find(std::string_view name) const {
  for (const auto& t : tensors_)
    if (t.name == name) return &t;
  return nullptr;
}

const Tensor& ModelFile::require(std::string_view name, DType dtype,
                                 std::initializer_list<int64_t> shape) const {
  const Tensor* t = find(name);
  const std::string field = "tensor " + std::string(name);
  if (!t) fail(field, "missing");
  if (t->dtype != dtype) fail(field, std::string("expected dtype ") + dtype_name(dtype));
  bool ok = t->shape.size() == shape.size();
  size_t i = 0;
  for (int64_t want : shape) {
    if (!ok) break;
    if (want >= 0 && t->shape[i] != want) ok = false;
    ++i;
  }
  if (!ok) {
    std::string s = "[";
    // Appended piecewise: GCC 12's -Wrestrict misfires on "," + string.
    for (int64_t want : shape) {
      if (s.size() > 1) s += ',';
      s += want < 0 ? std::string("*") : std::to_string(want);
    }
    fail(field, "expected shape " + s + "]");
  }
  return *t;
}

void ModelFile::fail(const std::string& field, const std::string& problem) const {
  throw ModelError(ModelError::Kind::kInconsistent, path_, field, problem);
}

}  // namespace candela::model
