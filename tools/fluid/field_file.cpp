#include "field_file.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace candela::fluid {
namespace {

constexpr char kMagic[4] = {'C', 'F', 'L', 'D'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderSize = 48;

void put_u32(std::vector<uint8_t>& b, uint32_t v) {
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k)));
}
void put_f64(std::vector<uint8_t>& b, double d) {
  uint64_t v;
  std::memcpy(&v, &d, 8);
  for (int k = 0; k < 8; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k)));
}
void put_f32(std::vector<uint8_t>& b, float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  put_u32(b, v);
}
uint32_t get_u32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}
double get_f64(const uint8_t* p) {
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= static_cast<uint64_t>(p[k]) << (8 * k);
  double d;
  std::memcpy(&d, &v, 8);
  return d;
}
float get_f32(const uint8_t* p) {
  const uint32_t v = get_u32(p);
  float f;
  std::memcpy(&f, &v, 4);
  return f;
}

}  // namespace

void write_field_file(const std::string& path, const FieldFrame& f) {
  const int w = f.temperature.width, h = f.temperature.height;
  std::vector<uint8_t> b;
  const size_t n = static_cast<size_t>(w) * h;
  b.reserve(kHeaderSize + n * 4 * (f.has_velocity ? 3 : 1));
  b.insert(b.end(), kMagic, kMagic + 4);
  put_u32(b, kVersion);
  put_u32(b, static_cast<uint32_t>(w));
  put_u32(b, static_cast<uint32_t>(h));
  put_u32(b, f.index);
  put_u32(b, f.has_velocity ? 1u : 0u);
  put_f64(b, f.time);
  put_f64(b, f.t_ambient);
  put_f64(b, f.t_reference);
  for (double t : f.temperature.data) put_f32(b, static_cast<float>(t));
  if (f.has_velocity) {
    for (double x : f.u.data) put_f32(b, static_cast<float>(x));
    for (double x : f.v.data) put_f32(b, static_cast<float>(x));
  }
  write_atomic(path, std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

FieldFrame read_field_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path, "", "a readable CFLD field file (cannot open it)");
  std::vector<uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (b.size() < kHeaderSize)
    throw ConfigError(path, "header",
                      "at least 48 bytes (file has " + std::to_string(b.size()) + ")");
  if (std::memcmp(b.data(), kMagic, 4) != 0)
    throw ConfigError(path, "magic", "\"CFLD\" at the start of the file");
  const uint32_t version = get_u32(&b[4]);
  if (version != kVersion)
    throw ConfigError(path, "version", "1 (file has " + std::to_string(version) + ")");
  const uint32_t w = get_u32(&b[8]), h = get_u32(&b[12]);
  if (w < 1 || w > 8192 || h < 1 || h > 8192)
    throw ConfigError(
        path, "width/height",
        "1..8192 cells each (file has " + std::to_string(w) + "x" + std::to_string(h) + ")");
  FieldFrame f;
  f.index = get_u32(&b[16]);
  const uint32_t flags = get_u32(&b[20]);
  if (flags & ~1u) throw ConfigError(path, "flags", "only bit 0 (velocity) may be set");
  f.has_velocity = (flags & 1u) != 0;
  f.time = get_f64(&b[24]);
  f.t_ambient = get_f64(&b[32]);
  f.t_reference = get_f64(&b[40]);
  if (!std::isfinite(f.time)) throw ConfigError(path, "time", "a finite number of seconds");
  if (!std::isfinite(f.t_ambient) || f.t_ambient <= 0.0)
    throw ConfigError(path, "t_ambient", "a finite temperature > 0 K");
  if (!std::isfinite(f.t_reference) || f.t_reference <= f.t_ambient)
    throw ConfigError(path, "t_reference", "a finite temperature above t_ambient");
  const size_t n = static_cast<size_t>(w) * h;
  const size_t want = kHeaderSize + n * 4 * (f.has_velocity ? 3 : 1);
  if (b.size() != want)
    throw ConfigError(path, "size",
                      std::to_string(want) + " bytes for " + std::to_string(w) + "x" +
                          std::to_string(h) + " cells (file has " + std::to_string(b.size()) + ")");
  auto read_grid = [&](Grid2& g, size_t offset, const char* name) {
    g = Grid2(static_cast<int>(w), static_cast<int>(h));
    for (size_t k = 0; k < n; ++k) {
      const float x = get_f32(&b[offset + 4 * k]);
      if (!std::isfinite(x))
        throw ConfigError(path, std::string(name) + "[" + std::to_string(k) + "]",
                          "a finite number");
      g.data[k] = x;
    }
  };
  read_grid(f.temperature, kHeaderSize, "temperature");
  if (f.has_velocity) {
    read_grid(f.u, kHeaderSize + n * 4, "u");
    read_grid(f.v, kHeaderSize + n * 8, "v");
  }
  return f;
}

}  // namespace candela::fluid
