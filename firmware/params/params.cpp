#include "params/params.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/file_read.h"

namespace candela {
namespace {

std::string describe(const toml::node& n) {
  std::ostringstream s;
  if (n.is_string()) {
    return '"' + echo_value(n.value<std::string>().value_or("")) + '"';
  } else if (n.is_table()) {
    s << "a table";
  } else if (n.is_array()) {
    s << "an array";
  } else {
    n.visit([&](auto&& v) { s << v; });
  }
  return s.str();
}

// Any TOML number as a double. toml++'s value<double>() refuses integers it
// cannot represent exactly (above 2^53): those would silently read as 0.
double as_double(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nan("");
}

std::string range(double min, double max) {
  std::ostringstream s;
  s << "[" << min << ", " << max << "]";
  return s.str();
}

}  // namespace

std::string echo_value(std::string_view v) {
  constexpr size_t kMaxEcho = 60;
  if (v.size() <= kMaxEcho) return std::string(v);
  return std::string(v.substr(0, kMaxEcho)) + "... (" + std::to_string(v.size()) + " characters)";
}

std::string resolve_relative(const std::string& scene_file, const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  const auto slash = scene_file.rfind('/');
  if (slash == std::string::npos || scene_file[0] == '<') return path;
  return scene_file.substr(0, slash + 1) + path;
}

ParamReader::ParamReader(const toml::table* table, std::string file, std::string prefix)
    : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

std::string ParamReader::key_path(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

bool ParamReader::has(std::string_view key) const { return table_ && table_->contains(key); }

void ParamReader::fail(std::string_view key, const std::string& expected) const {
  throw ConfigError(file_, key_path(key), expected);
}

const toml::node* ParamReader::get(std::string_view key) {
  used_.emplace(key);
  return table_ ? table_->get(key) : nullptr;
}

double ParamReader::number(std::string_view key, double def, double min, double max) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (!n->is_number())
    fail(key, "expected a number in " + range(min, max) + ", got " + describe(*n));
  const double v = as_double(*n);
  if (!std::isfinite(v) || v < min || v > max)
    fail(key, "expected a number in " + range(min, max) + ", got " + describe(*n));
  return v;
}

Fixed ParamReader::fixed(std::string_view key, double def, double min, double max) {
  const double v = number(key, def, min, max);
  if (!Fixed::in_range(v))  // a range wider than Q16.16 is a bug in the caller, not the scene
    fail(key, "expected a number in [-32767, 32767] (fixed point), got " + std::to_string(v));
  return Fixed::from_double(v);
}

int64_t ParamReader::integer(std::string_view key, int64_t def, int64_t min, int64_t max) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (!n->is_integer())
    fail(key, "expected an integer in " +
                  range(static_cast<double>(min), static_cast<double>(max)) + ", got " +
                  describe(*n));
  const int64_t v = n->value<int64_t>().value_or(0);
  if (v < min || v > max)
    fail(key, "expected an integer in " +
                  range(static_cast<double>(min), static_cast<double>(max)) + ", got " +
                  describe(*n));
  return v;
}

bool ParamReader::boolean(std::string_view key, bool def) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (!n->is_boolean()) fail(key, "expected true or false, got " + describe(*n));
  return n->value<bool>().value_or(def);
}

std::string ParamReader::string(std::string_view key, std::string_view def,
                                std::initializer_list<std::string_view> allowed) {
  const toml::node* n = get(key);
  std::string choices;
  for (auto a : allowed) choices += (choices.empty() ? "" : ", ") + std::string(a);
  if (!n) return std::string(def);
  if (!n->is_string())
    fail(key, allowed.size() ? "expected one of " + choices + ", got " + describe(*n)
                             : "expected a string, got " + describe(*n));
  std::string v = *n->value<std::string>();
  if (allowed.size()) {
    for (auto a : allowed)
      if (a == v) return v;
    fail(key, "expected one of " + choices + ", got \"" + echo_value(v) + "\"");
  }
  return v;
}

Vec3 ParamReader::vec3(std::string_view key, Vec3 def) {
  const toml::node* n = get(key);
  if (!n) return def;
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3) fail(key, "expected an array of 3 numbers, got " + describe(*n));
  float v[3];
  for (size_t i = 0; i < 3; ++i) {
    const toml::node* e = a->get(i);
    if (!e->is_number()) fail(key, "expected an array of 3 numbers, got " + describe(*n));
    v[i] = static_cast<float>(as_double(*e));
    if (!std::isfinite(v[i])) fail(key, "expected finite numbers");
    if (std::fabs(v[i]) > 1e6f)  // metres: far beyond any scene, and float maths
      fail(key, "expected numbers within +-1e6, got " + describe(*e));
  }
  return {v[0], v[1], v[2]};
}

std::vector<double> ParamReader::numbers(std::string_view key, double min, double max,
                                         size_t max_count) {
  const toml::node* n = get(key);
  std::vector<double> out;
  if (!n) return out;
  const std::string what = "expected an array of at most " + std::to_string(max_count) +
                           " numbers in " + range(min, max);
  const toml::array* a = n->as_array();
  if (!a) fail(key, what + ", got " + describe(*n));
  if (a->size() > max_count) fail(key, what + ", got " + std::to_string(a->size()) + " numbers");
  for (size_t i = 0; i < a->size(); ++i) {
    const toml::node* e = a->get(i);
    const double v = e->is_number() ? as_double(*e) : std::nan("");
    if (!std::isfinite(v) || v < min || v > max)
      fail(key, what + ", got " + describe(*e) + " at index " + std::to_string(i));
    out.push_back(v);
  }
  return out;
}

Vec3 ParamReader::color(std::string_view key, Vec3 def) {
  const toml::node* n = table_ ? table_->get(key) : nullptr;
  if (n && n->is_string()) {
    used_.emplace(key);
    const std::string s = *n->value<std::string>();
    unsigned r = 0, g = 0, b = 0;
    if (s.size() != 7 || s[0] != '#' || std::sscanf(s.c_str() + 1, "%2x%2x%2x", &r, &g, &b) != 3)
      fail(key,
           "expected a colour \"#rrggbb\" or [r, g, b] in 0..1, got \"" + echo_value(s) + "\"");
    return {r / 255.0f, g / 255.0f, b / 255.0f};
  }
  if (n && !n->is_array()) {
    used_.emplace(key);
    fail(key, "expected a colour \"#rrggbb\" or [r, g, b] in 0..1, got " + describe(*n));
  }
  const Vec3 c = vec3(key, def);
  for (float x : {c.x, c.y, c.z})
    if (x < 0 || x > 1) fail(key, "expected colour components in [0, 1]");
  return c;
}

std::string ParamReader::path(std::string_view key, std::string_view def) {
  const std::string p = string(key, def);
  if (p.empty() || !has(key)) return p;
  const std::string full = resolve_relative(file_, p);
  // Opened non-blocking and checked with fstat: a FIFO or device named here
  // is refused now, never read (core/file_read.h).
  const std::string why = regular_file_problem(full);
  if (!why.empty())
    fail(key, "expected a readable regular file, but '" + echo_value(full) + "': " + why);
  return full;
}

ParamReader ParamReader::table(std::string_view key) {
  const toml::node* n = get(key);
  if (n && !n->is_table()) fail(key, "expected a table, got " + describe(*n));
  return ParamReader(n ? n->as_table() : nullptr, file_, key_path(key));
}

std::vector<ParamReader> ParamReader::table_array(std::string_view key) {
  const toml::node* n = get(key);
  std::vector<ParamReader> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (a && a->empty()) return out;
  if (!a || !a->is_array_of_tables())
    fail(key, "expected an array of tables ([[" + key_path(key) + "]]), got " + describe(*n));
  for (size_t i = 0; i < a->size(); ++i)
    out.emplace_back(a->get(i)->as_table(), file_, key_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

std::vector<std::string> ParamReader::keys() const {
  std::vector<std::string> out;
  if (table_)
    for (const auto& [k, v] : *table_) out.emplace_back(k.str());
  return out;
}

void ParamReader::finish() const {
  if (!table_) return;
  for (const auto& [k, v] : *table_) {
    if (!used_.contains(k.str())) {
      std::string known;
      for (const auto& u : used_) known += (known.empty() ? "" : ", ") + u;
      throw ConfigError(file_, key_path(echo_value(k.str())),
                        "unknown key (known here: " + known + ")");
    }
  }
}

}  // namespace candela
