// Reads one TOML table of parameters with validation. Every problem becomes a
// ConfigError naming the file, the full key (e.g. element[2].height) and what
// was expected; finish() rejects keys nobody asked for (typos).
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/fixed.h"
#include "gl/math.h"

namespace candela {

class ParamReader {
 public:
  ParamReader(const toml::table* table, std::string file, std::string prefix);

  const std::string& file() const { return file_; }
  std::string key_path(std::string_view key) const;
  bool has(std::string_view key) const;
  // Marks a key as read by the caller itself (so finish() accepts it).
  void consume(std::string_view key) { used_.emplace(key); }

  double number(std::string_view key, double def, double min, double max);
  // A number held as Q16.16: [min, max] must lie inside what Fixed holds.
  Fixed fixed(std::string_view key, double def, double min, double max);
  int64_t integer(std::string_view key, int64_t def, int64_t min, int64_t max);
  bool boolean(std::string_view key, bool def);
  std::string string(std::string_view key, std::string_view def,
                     std::initializer_list<std::string_view> allowed = {});
  Vec3 vec3(std::string_view key, Vec3 def);
  // An array of at most max_count numbers, each in [min, max] (absent: empty).
  std::vector<double> numbers(std::string_view key, double min, double max, size_t max_count);
  // [r, g, b] in 0..1, or "#rrggbb".
  Vec3 color(std::string_view key, Vec3 def);
  // A file named relative to the scene file; must exist and be readable if given.
  std::string path(std::string_view key, std::string_view def = {});
  // A nested table (empty reader if absent). Its keys count as used.
  ParamReader table(std::string_view key);
  // An array of tables ([[key]]): one reader per entry, prefixed key[i]; empty if absent.
  std::vector<ParamReader> table_array(std::string_view key);
  // The table's keys, in the file's order (a table whose keys are data:
  // the kiosk's [schedule] days and time ranges).
  std::vector<std::string> keys() const;
  // Throws on the first key that no call asked for.
  void finish() const;

  [[noreturn]] void fail(std::string_view key, const std::string& expected) const;

 private:
  const toml::node* get(std::string_view key);
  const toml::table* table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string, std::less<>> used_;
};

// A value as echoed in a message: cut short (a 10 MB bad string must not
// become a 10 MB log line), saying how long it was.
std::string echo_value(std::string_view v);

// Where relative paths in a scene are resolved: the scene file's folder.
std::string resolve_relative(const std::string& scene_file, const std::string& path);

}  // namespace candela
