// Writes Candela model files (see model_file.h for the layout).
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "model/model_file.h"

namespace candela::model {

class ModelWriter {
 public:
  // The free-form "model" object of the metadata.
  void set_info(nlohmann::json info) { info_ = std::move(info); }
  void add(const std::string& name, DType dtype, std::vector<int64_t> shape,
           std::span<const uint8_t> bytes);
  void add_f32(const std::string& name, std::vector<int64_t> shape, std::span<const float> v) {
    add(name, DType::kF32, std::move(shape), as_bytes(v));
  }
  void add_i32(const std::string& name, std::vector<int64_t> shape, std::span<const int32_t> v) {
    add(name, DType::kI32, std::move(shape), as_bytes(v));
  }
  // The whole file. Format version and checksum are filled in here.
  std::vector<uint8_t> bytes(int version = kFormatVersion) const;
  // Atomically (temporary file + rename). Throws RuntimeError on failure.
  void write(const std::string& path) const;

 private:
  template <class T>
  static std::span<const uint8_t> as_bytes(std::span<const T> v) {
    return {reinterpret_cast<const uint8_t*>(v.data()), v.size_bytes()};
  }
  struct Entry {
    DType dtype;
    std::vector<int64_t> shape;
    std::vector<uint8_t> bytes;
  };
  nlohmann::json info_ = nlohmann::json::object();
  // Kept in name order (the header's order), so the same model always gives
  // the same bytes; adding a name again replaces it.
  std::map<std::string, Entry> entries_;
};

// Images quantised to 8 or 16 bits, each with its own scale and offset:
// value = offset + scale * q.
struct QuantisedSet {
  DType dtype = DType::kU16;
  std::vector<uint8_t> bytes;  // count x pixels, little-endian
  std::vector<float> scale, offset;
};
QuantisedSet quantise_images(const float* images, int count, size_t pixels, DType dtype);
// Adds NAME.q [count,h,w], NAME.scale [count], NAME.offset [count].
void add_quantised(ModelWriter& w, const std::string& name, const QuantisedSet& q, int count,
                   int width, int height);

}  // namespace candela::model
