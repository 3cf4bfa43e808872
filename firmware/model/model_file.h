// The Candela model file: a safetensors-style container that the runtime reads
// once into page-aligned memory and uses in place (no Eigen, no parsing copies).
//
//   [u64 little-endian header length N][N bytes of JSON header, space padded]
//   [tensor data; every tensor starts on a 64-byte boundary of the file]
//
// The header maps tensor names to {"dtype","shape","data_offsets":[begin,end]}
// (offsets relative to the start of the data section, as in safetensors) and
// holds "__metadata__": {"format":"candela-model","version":1,
// "checksum":"crc32:xxxxxxxx","data_bytes":n,"model":{...}}. Unlike plain
// safetensors, tensors are aligned (so the data section may hold padding) and
// the metadata is nested JSON. The CRC-32 covers the header with the checksum
// entry removed (canonical dump) followed by the whole data section.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace candela::model {

inline constexpr std::string_view kFormatName = "candela-model";
inline constexpr int kFormatVersion = 1;
inline constexpr size_t kAlignment = 64;
// Headers beyond this are not ours (and would let a corrupt length allocate wildly).
inline constexpr uint64_t kMaxHeaderBytes = 64u << 20;

enum class DType : uint8_t { kU8, kU16, kI32, kF32 };
size_t dtype_size(DType t);
const char* dtype_name(DType t);  // safetensors spelling: U8, U16, I32, F32

struct Tensor {
  std::string name;
  DType dtype = DType::kU8;
  std::vector<int64_t> shape;
  const uint8_t* data = nullptr;  // inside the loaded file, kAlignment-aligned
  size_t bytes = 0;

  size_t count() const { return bytes / dtype_size(dtype); }
  template <class T>
  std::span<const T> view() const {
    return {reinterpret_cast<const T*>(data), bytes / sizeof(T)};
  }
};

// Every way a model file can be refused, each with its own message; what()
// reads "<file>: <field>: <problem>".
class ModelError : public ConfigError {
 public:
  enum class Kind { kIo, kTruncated, kHeader, kVersion, kChecksum, kInconsistent };
  ModelError(Kind kind, std::string file, std::string field, std::string problem)
      : ConfigError(std::move(file), std::move(field), std::move(problem)), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};
const char* to_string(ModelError::Kind k);

// A validated, read-only model file. Cheap to copy (shares the loaded bytes).
class ModelFile {
 public:
  // Reads the file into private memory (never mapped: overwriting the file later
  // cannot touch a loaded model) and checks framing, header, version and checksum.
  static ModelFile open(const std::string& path);
  // The same checks on a buffer in memory (tests, fuzzing); `name` is used in errors.
  static ModelFile from_bytes(std::vector<uint8_t> bytes, const std::string& name);
  // The same checks on bytes that live as long as the program (a model built
  // into the binary), read in place: no copy. At least 4-byte aligned.
  static ModelFile from_static(std::string_view bytes, const std::string& name);

  const std::string& path() const { return path_; }
  int version() const { return version_; }
  uint32_t checksum() const { return checksum_; }
  size_t file_size() const;
  size_t header_bytes() const { return header_bytes_; }
  // A model built into the binary is read in place from the binary's file
  // mapping. Once [data, data + bytes) of it has been copied where it is used
  // (images uploaded to the GPU), the pages wholly inside that range are
  // given back (madvise MADV_DONTNEED): the process stops holding them
  // resident, and reading them again pages them in from the file, unchanged.
  // Does nothing for a model read from a file or a buffer (its bytes are the
  // only copy). Returns the bytes given back.
  size_t give_back_pages(const uint8_t* data, size_t bytes) const;
  // The "model" object of the metadata (free-form description, checked by FlameModel).
  const nlohmann::json& info() const { return info_; }
  const std::vector<Tensor>& tensors() const { return tensors_; }
  const Tensor* find(std::string_view name) const;
  // The tensor, or ModelError(kInconsistent) if it is missing or has another
  // dtype or shape (-1 in `shape` matches any extent).
  const Tensor& require(std::string_view name, DType dtype,
                        std::initializer_list<int64_t> shape) const;
  // Throws ModelError(kInconsistent) naming `field`.
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const;

 private:
  struct Storage;
  static ModelFile parse(std::shared_ptr<const Storage> storage, const std::string& name);

  std::shared_ptr<const Storage> storage_;
  std::string path_;
  int version_ = 0;
  uint32_t checksum_ = 0;
  size_t header_bytes_ = 0;
  nlohmann::json info_;
  std::vector<Tensor> tensors_;
};

// CRC-32 of the canonical header (without the checksum entry) and the data.
uint32_t model_checksum(const nlohmann::json& header_without_checksum, const uint8_t* data,
                        size_t data_bytes);

}  // namespace candela::model
