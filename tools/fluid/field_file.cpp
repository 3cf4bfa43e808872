#include "field_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "model/model_file.h"
#include "model/model_writer.h"

namespace candela::fluid {
namespace {

constexpr const char* kKind = "fluid-field";
constexpr int kVersion = 1;

std::vector<float> to_f32(const Grid2& g) { return {g.data.begin(), g.data.end()}; }

}  // namespace

void write_field_file(const std::string& path, const FieldFrame& f) {
  const int w = f.temperature.width, h = f.temperature.height;
  model::ModelWriter mw;
  mw.set_info({{"kind", kKind},
               {"version", kVersion},
               {"frame", f.index},
               {"time", f.time},
               {"t_ambient", f.t_ambient},
               {"t_reference", f.t_reference},
               {"velocity", f.has_velocity}});
  mw.add_f32("temperature", {h, w}, to_f32(f.temperature));
  if (f.has_velocity) {
    mw.add_f32("u", {h, w}, to_f32(f.u));
    mw.add_f32("v", {h, w}, to_f32(f.v));
  }
  mw.write(path);
}

FieldFrame read_field_file(const std::string& path) {
  const model::ModelFile file = model::ModelFile::open(path);
  const nlohmann::json& info = file.info();
  auto fail = [&](const std::string& field, const std::string& expected) {
    throw ConfigError(path, field, expected);
  };
  auto kind = info.find("kind");
  if (kind == info.end() || !kind->is_string() || kind->get<std::string>() != kKind)
    fail("model.kind", "\"fluid-field\" (a field file written by candela-tool simulate)");
  auto version = info.find("version");
  if (version == info.end() || !version->is_number_integer() || version->get<int64_t>() != kVersion)
    fail("model.version",
         "1 (file has " + (version == info.end() ? std::string("none") : version->dump()) + ")");
  auto number = [&](const char* key) {
    auto it = info.find(key);
    if (it == info.end() || !it->is_number() || !std::isfinite(it->get<double>()))
      fail(std::string("model.") + key, "a finite number");
    return it->get<double>();
  };
  FieldFrame f;
  auto frame = info.find("frame");
  if (frame == info.end() || !frame->is_number_unsigned() || frame->get<uint64_t>() > UINT32_MAX)
    fail("model.frame", "a frame index in [0, 4294967295]");
  f.index = frame->get<uint32_t>();
  auto velocity = info.find("velocity");
  if (velocity == info.end() || !velocity->is_boolean()) fail("model.velocity", "true or false");
  f.has_velocity = velocity->get<bool>();
  f.time = number("time");
  f.t_ambient = number("t_ambient");
  f.t_reference = number("t_reference");
  if (f.t_ambient <= 0.0) fail("model.t_ambient", "a finite temperature > 0 K");
  if (f.t_reference <= f.t_ambient)
    fail("model.t_reference", "a finite temperature above t_ambient");
  const model::Tensor& t = file.require("temperature", model::DType::kF32, {-1, -1});
  const int64_t h = t.shape[0], w = t.shape[1];
  if (w < 1 || w > 8192 || h < 1 || h > 8192)
    fail("tensor temperature",
         "1..8192 cells each way (file has " + std::to_string(w) + "x" + std::to_string(h) + ")");
  const size_t expect_tensors = f.has_velocity ? 3 : 1;
  if (file.tensors().size() != expect_tensors)
    fail("tensors", std::string(f.has_velocity ? "temperature, u and v" : "temperature only") +
                        " (file has " + std::to_string(file.tensors().size()) + " tensors)");
  auto read_grid = [&](Grid2& g, const char* name) {
    const model::Tensor& src = file.require(name, model::DType::kF32, {h, w});
    g = Grid2(static_cast<int>(w), static_cast<int>(h));
    const auto values = src.view<float>();
    for (size_t k = 0; k < values.size(); ++k) {
      if (!std::isfinite(values[k]))
        fail(std::string(name) + "[" + std::to_string(k) + "]", "a finite number");
      g.data[k] = values[k];
    }
  };
  read_grid(f.temperature, "temperature");
  if (f.has_velocity) {
    read_grid(f.u, "u");
    read_grid(f.v, "v");
  }
  return f;
}

}  // namespace candela::fluid
