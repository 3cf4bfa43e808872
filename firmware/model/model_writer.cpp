#include "model/model_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"

namespace candela::model {

void ModelWriter::add(const std::string& name, DType dtype, std::vector<int64_t> shape,
                      std::span<const uint8_t> bytes) {
  entries_[name] = Entry{dtype, std::move(shape), {bytes.begin(), bytes.end()}};
}

std::vector<uint8_t> ModelWriter::bytes(int version) const {
  nlohmann::json header = nlohmann::json::object();
  uint64_t offset = 0;
  for (const auto& [name, e] : entries_) {
    offset = (offset + kAlignment - 1) / kAlignment * kAlignment;
    header[name] = {{"dtype", dtype_name(e.dtype)},
                    {"shape", e.shape},
                    {"data_offsets", {offset, offset + e.bytes.size()}}};
    offset += e.bytes.size();
  }
  const uint64_t data_bytes = offset;
  std::vector<uint8_t> data(data_bytes, 0);
  offset = 0;
  for (const auto& [name, e] : entries_) {
    offset = (offset + kAlignment - 1) / kAlignment * kAlignment;
    std::copy(e.bytes.begin(), e.bytes.end(), data.begin() + static_cast<ptrdiff_t>(offset));
    offset += e.bytes.size();
  }
  header["__metadata__"] = {{"format", std::string(kFormatName)},
                            {"version", version},
                            {"data_bytes", data_bytes},
                            {"model", info_}};
  const uint32_t crc = model_checksum(header, data.data(), data.size());
  char buf[32];
  std::snprintf(buf, sizeof buf, "crc32:%08x", crc);
  header["__metadata__"]["checksum"] = buf;
  std::string text = header.dump();
  // Pad with spaces (valid JSON whitespace) so the data starts aligned.
  while ((8 + text.size()) % kAlignment != 0) text.push_back(' ');
  std::vector<uint8_t> out(8 + text.size() + data.size());
  uint64_t n = text.size();
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(n >> (8 * i));
  std::copy(text.begin(), text.end(), out.begin() + 8);
  std::copy(data.begin(), data.end(), out.begin() + 8 + static_cast<ptrdiff_t>(text.size()));
  return out;
}

void ModelWriter::write(const std::string& path) const {
  const std::vector<uint8_t> b = bytes();
  write_atomic(path, std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

QuantisedSet quantise_images(const float* images, int count, size_t pixels, DType dtype) {
  QuantisedSet q;
  q.dtype = dtype;
  const int bits = dtype == DType::kU8 ? 8 : 16;
  const float levels = static_cast<float>((1 << bits) - 1);
  q.bytes.resize(static_cast<size_t>(count) * pixels * (bits / 8));
  q.scale.resize(count);
  q.offset.resize(count);
  for (int i = 0; i < count; ++i) {
    const float* img = images + static_cast<size_t>(i) * pixels;
    auto [lo, hi] = std::minmax_element(img, img + pixels);
    const float range = *hi - *lo;
    const float scale = range > 0 ? range / levels : 1.0f;
    q.offset[i] = *lo;
    q.scale[i] = scale;
    for (size_t p = 0; p < pixels; ++p) {
      float v = std::nearbyint((img[p] - *lo) / scale);
      auto u = static_cast<uint32_t>(std::clamp(v, 0.0f, levels));
      size_t at = static_cast<size_t>(i) * pixels + p;
      if (bits == 8) {
        q.bytes[at] = static_cast<uint8_t>(u);
      } else {
        q.bytes[2 * at] = static_cast<uint8_t>(u & 0xff);
        q.bytes[2 * at + 1] = static_cast<uint8_t>(u >> 8);
      }
    }
  }
  return q;
}

void add_quantised(ModelWriter& w, const std::string& name, const QuantisedSet& q, int count,
                   int width, int height) {
  w.add(name + ".q", q.dtype, {count, height, width}, q.bytes);
  w.add_f32(name + ".scale", {count}, q.scale);
  w.add_f32(name + ".offset", {count}, q.offset);
}

}  // namespace candela::model
