#include "elements/candle/candle_params.h"

#include <cmath>
#include <mutex>
#include <span>

#include "core/error.h"
#include "embedded_noise_tables.h"
#include "params/params.h"

namespace candela {
namespace {

constexpr double kBuiltinBetas[] = {1.0, 1.4, 2.0, 2.4, 2.8};

struct ChannelInfo {
  const char* table;  // sub-table: calm or breeze
  const char* name;   // key prefix
  double beta;        // the paper's beta
  double rate;        // samples per second: a little different per channel so
                      // the candle's channels never fall into step
};
// Betas: Table 2 gives ranges (2.0-2.8, 1.0-1.8) for the breeze: their
// middles. Calm: Table 1's betas (2.8 sway and width, 2.0 stretch) put
// nearly all the motion in the tables' slowest components, and the outline
// then decorrelates in 0.8 s where real calm candles take 0.24-0.37 s
// (../shared/eval, tau_s); sway, width and stretch use 1.4 here (a scene may
// ask for the paper's betas), and the tip flicker (beyond the paper) is
// near-pink. Rates are table samples per second (the paper gives none): with
// the 32768-sample tables every channel's period is 7-18 s, each different.
constexpr ChannelInfo kChannels[kNoiseChannels] = {
    {"calm", "sway", 1.4, 1800},    {"calm", "tilt", 2.8, 2892},
    {"calm", "stretch", 1.4, 3000}, {"calm", "width", 1.4, 1900},
    {"calm", "flicker", 1.0, 4800}, {"breeze", "lean", 2.4, 3176},
    {"breeze", "tilt", 2.4, 3064},  {"breeze", "stretch", 1.4, 2648},
    {"breeze", "width", 2.4, 2936}, {"breeze", "turbulence", 2.0, 3301},
};

std::string beta_choices() {
  std::string s;
  for (double b : kBuiltinBetas) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.1f", b);
    s += (s.empty() ? "" : ", ") + std::string(buf);
  }
  return s;
}

void read_noise(ParamReader& r, int channel, NoiseSource& n) {
  const std::string name = kChannels[channel].name;
  n.rate = r.fixed(name + "_rate", n.rate.to_double(), 1, 8192);
  const std::string beta_key = name + "_beta";
  const std::string table_key = name + "_table";
  if (r.has(table_key)) {
    const std::string path = r.path(table_key);
    try {
      n.table = std::make_shared<const NoiseTable>(NoiseTable::load(path));
    } catch (const std::exception& e) {
      r.fail(table_key, std::string("expected a noise table (candela-tool noise): ") + e.what());
    }
    n.beta = n.table->info().beta_milli / 1000.0;
  }
  if (r.has(beta_key)) {
    if (r.has(table_key))
      r.fail(beta_key, "give either " + beta_key + " or " + table_key + ", not both");
    const double b = r.number(beta_key, n.beta, 0, 10);
    if (!is_builtin_beta(b))
      r.fail(beta_key, "expected one of the built-in betas " + beta_choices() +
                           " (or name your own table with " + table_key + ")");
    n.beta = b;
    n.table.reset();
  }
}

}  // namespace

bool is_builtin_beta(double beta) {
  for (double b : kBuiltinBetas)
    if (std::abs(b - beta) < 1e-9) return true;
  return false;
}

const NoiseTable& builtin_noise_table(double beta, int variant) {
  static std::once_flag once;
  static NoiseTable tables[5][3];
  std::call_once(once, [] {
    for (int i = 0; i < 5; ++i)
      for (int v = 0; v < 3; ++v) {
        char name[32];
        std::snprintf(name, sizeof name, "b%02d_%d.cnoise",
                      static_cast<int>(std::lround(kBuiltinBetas[i] * 10)), v);
        tables[i][v] =
            NoiseTable::parse(noise_tables::find(name), std::string("<built-in ") + name + ">");
      }
  });
  int best = 0;
  for (int i = 1; i < 5; ++i)
    if (std::abs(kBuiltinBetas[i] - beta) < std::abs(kBuiltinBetas[best] - beta)) best = i;
  return tables[best][variant % 3];
}

CandleParams::CandleParams() {
  for (int c = 0; c < kNoiseChannels; ++c) {
    noise[c].beta = kChannels[c].beta;
    noise[c].rate = Fixed::from_int(static_cast<int32_t>(kChannels[c].rate));
  }
}

namespace {
// One number of a parameter table: its key, where it goes, its range.
struct Field {
  const char* key;
  Fixed CandleParams::*member;
  double lo, hi;
};
// A table of the [[element]] (calm = { ... }), its numbers in the order they
// are read, and the noise channels it tunes (first..last; -1: none).
struct Table {
  const char* name;
  std::span<const Field> fields;
  int first_channel = -1, last_channel = -1;
};
using P = CandleParams;
constexpr Field kCalm[] = {
    {"sway_left", &P::sway_left, -90, 0},
    {"sway_right", &P::sway_right, 0, 90},
    {"tilt_front", &P::tilt_front, -90, 0},
    {"tilt_rear", &P::tilt_rear, 0, 90},
    {"stretch_low", &P::calm_stretch_low, 0.01, 4},
    {"stretch_high", &P::calm_stretch_high, 0.01, 4},
    {"width_thin", &P::calm_width_thin, 0.01, 4},
    {"width_thick", &P::calm_width_thick, 0.01, 4},
    {"flicker", &P::flicker, 0, 0.5},
    {"turbulence", &P::calm_turbulence, 0, 1},
};
constexpr Field kBreeze[] = {
    {"lean", &P::lean, 0, 89},
    {"tilt", &P::breeze_tilt, 0, 89},
    {"stretch_low", &P::breeze_stretch_low, 0.01, 4},
    {"stretch_high", &P::breeze_stretch_high, 0.01, 4},
    {"width_thin", &P::breeze_width_thin, 0.01, 4},
    {"width_thick", &P::breeze_width_thick, 0.01, 4},
    {"full_speed", &P::full_speed, 0.05, 30},
    {"flutter", &P::flutter, 0, 1},
    {"turbulence", &P::turbulence, 0, 0.5},
    {"turbulence_lag", &P::turbulence_lag, 0, 2},
    {"bend", &P::bend, 0, 0.9},
};
constexpr Field kWick[] = {
    {"stick_angle", &P::stick_angle, 1, 89},
    {"angle", &P::wick_angle, -45, 45},
    {"stick_depth", &P::stick_depth, 0, 0.5},
};
constexpr Field kPendulum[] = {
    {"frequency", &P::pendulum_hz, 0.1, 10},
    {"damping", &P::pendulum_damping, 0.02, 2},
};
constexpr Field kExtinguish[] = {
    {"speed", &P::extinguish_speed, 0.1, 100},
    {"relight_seconds", &P::relight_seconds, 0.1, 3600},
    {"smoke_seconds", &P::smoke_seconds, 0, 30},
    {"regrow_seconds", &P::regrow_seconds, 0.05, 30},
};
const Table kTables[] = {
    {"calm", kCalm, kCalmSway, kCalmFlicker},
    {"breeze", kBreeze, kBreezeLean, kTurbulence},
    {"wick", kWick},
    {"pendulum", kPendulum},
    {"extinguish", kExtinguish},
};
}  // namespace

CandleParams parse_candle_params(ParamReader& r, const CandleParams& base) {
  CandleParams p = base;
  for (const Table& table : kTables) {
    ParamReader t = r.table(table.name);
    for (const Field& f : table.fields)
      p.*f.member = t.fixed(f.key, (p.*f.member).to_double(), f.lo, f.hi);
    for (int ch = table.first_channel; ch >= 0 && ch <= table.last_channel; ++ch)
      read_noise(t, ch, p.noise[ch]);
    t.finish();
  }
  return p;
}

}  // namespace candela
