#include "sim_dataset.h"

#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace candela::fluid {
namespace {

std::string numbered(const std::string& dir, const char* sub, const char* stem, int index,
                     const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%06d.%s", stem, index, ext);
  return (std::filesystem::path(dir) / sub / name).string();
}

}  // namespace

std::string frame_path(const std::string& dir, int index) {
  return numbered(dir, "frames", "frame", index, "png");
}
std::string field_path(const std::string& dir, int index) {
  return numbered(dir, "fields", "field", index, "cfld");
}
std::string manifest_path(const std::string& dir) {
  return (std::filesystem::path(dir) / "manifest.toml").string();
}

void write_manifest(const std::string& dir, const SimManifest& m) {
  toml::table clip{
      {"name", m.name},     {"source", m.source}, {"command", m.command},
      {"frames", m.frames}, {"fps", m.fps},       {"width", m.width},
      {"height", m.height}, {"colour", m.colour}, {"frame_pattern", "frames/frame_%06d.png"}};
  toml::table manifest{{"clip", std::move(clip)}};
  if (m.has_fields)
    manifest.insert("fields", toml::table{{"pattern", "fields/field_%06d.cfld"},
                                          {"format", "fluid-field 1"},
                                          {"width", m.grid_width},
                                          {"height", m.grid_height},
                                          {"t_ambient", m.t_ambient},
                                          {"t_reference", m.t_reference}});
  std::ostringstream o;
  o << "# Candela flame clip: PNG frames (+ optional simulation fields).\n"
    << toml::toml_formatter(manifest) << "\n";
  write_atomic(manifest_path(dir), o.str());
}

SimManifest read_manifest(const std::string& dir) {
  const std::string path = manifest_path(dir);
  if (!std::filesystem::exists(path))
    throw ConfigError(path, "", "a manifest written by candela-tool simulate (file not found)");
  toml::table tbl;
  try {
    tbl = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "valid TOML (" << e.description() << " at line " << e.source().begin.line << ")";
    throw ConfigError(path, "", msg.str());
  }
  SimManifest m;
  auto need_str = [&](const char* table, const char* key) {
    auto v = tbl[table][key].value<std::string>();
    if (!v) throw ConfigError(path, std::string(table) + "." + key, "a string");
    return *v;
  };
  auto need_int = [&](const char* table, const char* key, int64_t lo, int64_t hi) {
    auto v = tbl[table][key].value<int64_t>();
    if (!v || *v < lo || *v > hi)
      throw ConfigError(path, std::string(table) + "." + key,
                        "an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(*v);
  };
  auto need_num = [&](const char* table, const char* key, double lo, double hi) {
    auto v = tbl[table][key].value<double>();
    if (!v || !std::isfinite(*v) || *v < lo || *v > hi)
      throw ConfigError(path, std::string(table) + "." + key, "a number in the valid range");
    return *v;
  };
  if (!tbl["clip"].is_table()) throw ConfigError(path, "clip", "a [clip] table");
  m.name = need_str("clip", "name");
  m.source = need_str("clip", "source");
  if (auto c = tbl["clip"]["command"].value<std::string>()) m.command = *c;
  m.frames = need_int("clip", "frames", 1, 10000000);
  m.fps = need_num("clip", "fps", 0.001, 10000.0);
  m.width = need_int("clip", "width", 1, 65536);
  m.height = need_int("clip", "height", 1, 65536);
  m.colour = need_str("clip", "colour");
  if (m.colour != "gray" && m.colour != "blackbody" && m.colour != "rgb")
    throw ConfigError(path, "clip.colour", "\"gray\", \"blackbody\" or \"rgb\"");
  m.has_fields = tbl["fields"].is_table();
  if (m.has_fields) {
    m.grid_width = need_int("fields", "width", 1, 8192);
    m.grid_height = need_int("fields", "height", 1, 8192);
    m.t_ambient = need_num("fields", "t_ambient", 1e-6, 1e9);
    m.t_reference = need_num("fields", "t_reference", 1e-6, 1e9);
    if (m.t_reference <= m.t_ambient)
      throw ConfigError(path, "fields.t_reference", "a temperature above fields.t_ambient");
  }
  return m;
}

}  // namespace candela::fluid
