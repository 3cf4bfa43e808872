// Realism yardsticks for flame clips: the measures of ../shared/eval/flame_features.py
// (appearance and motion features, scale-free) and ../shared/eval/realism.py (I/H/X/W
// time series, their spectra, log-spectral distances, repeats), computed the same way
// so the numbers agree with the scripts'. A clip is a folder of PNG frames of one flame
// on black; see tools/measure/README.md for what each number means.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace candela::measure {

// Gray frames (0..255), all the same size, stored one after another.
struct Frames {
  int width = 0;
  int height = 0;
  int count = 0;
  std::vector<uint8_t> pixels;

  const uint8_t* frame(int t) const {
    return pixels.data() + static_cast<size_t>(t) * width * height;
  }
  uint8_t* frame(int t) { return pixels.data() + static_cast<size_t>(t) * width * height; }
  size_t frame_size() const { return static_cast<size_t>(width) * height; }
};

struct LoadLimits {
  int max_frames = 900;  // the scripts' limit (flame_features.load)
  int max_side = 8192;   // per frame, pixels
  // Raw frames and, for the features, the frames scaled to a 128-px flame are
  // each held in memory at once; a folder (or a tiny flame in a huge frame)
  // that would need more stops with an error instead.
  size_t max_bytes = size_t{2} << 30;
};

// The first `max_frames` *.png files of `dir` (case-insensitive suffix, sorted
// by name), converted to gray as PIL's convert('L') does. Throws ConfigError
// naming the folder or the file: no frames, an unreadable PNG, mixed sizes,
// frames too large.
Frames load_frames(const std::string& dir, const LoadLimits& limits = {});

// PIL's Image.resize((w, h), Image.BILINEAR) of 8-bit gray frames: a separable
// triangle filter whose support grows with the downscale factor, fixed-point
// (22-bit) coefficients, horizontal pass rounded to 8 bits, then vertical.
Frames resize_bilinear_pil(const Frames& in, int width, int height);

// --- flame_features.py ---
inline constexpr double kFlameThreshold = 0.25;  // flame = gray > 0.25
inline constexpr int kNormHeight = 128;          // median flame height after normalising

struct Features {
  int frames = 0;
  double fps = 0;
  double tau_s = 0;       // detail decorrelation time (autocorrelation < 0.5), seconds
  double sharp = 0;       // mean |grad| on the edge band 0.15..0.6
  double spat_slope = 0;  // log-log slope of the radial spatial power spectrum
  double iso = 0;         // perimeter^2 / (4 pi area) of the flame mask
  double parts = 0;       // pieces per frame (>= 0.5% of the largest)
  double area_cv = 0;     // std / mean of the flame area over time
  double core = 0;        // share of flame pixels >= 0.95
};
// The feature names in the scripts' order, and one by name.
const std::vector<std::string>& feature_names();
double feature(const Features& f, const std::string& name);

// Per-frame flame height (rows from the lowest to the highest whose max > 0.25).
std::vector<double> heights(const Frames& v);
// Scales so the median flame height is 128 px. Throws ConfigError(where, ...) if
// no flame is found (median height < 4) or the result would exceed the limits.
Frames normalise(const Frames& raw, const std::string& where, const LoadLimits& limits = {});
// The parts of the features, on normalised frames (exposed for tests).
double tau(const Frames& v, double fps);
double sharpness(const Frames& v);
struct Box {
  int y0, y1, x0, x1;
};
Box flame_box(const Frames& v);
double spatial_slope(const Frames& v, const Box& box);
struct ShapeStats {
  double iso, parts, area_cv;
};
ShapeStats shape_stats(const Frames& v);
double core(const Frames& v);
// All features of raw frames (normalises first).
Features features(const Frames& raw, double fps, const std::string& where,
                  const LoadLimits& limits = {});

// --- realism.py ---
struct Series {
  std::vector<double> I, H, X, W;  // brightness, height, sway (centroid x), width
};
inline constexpr const char* kSeriesNames[4] = {"I", "H", "X", "W"};
const std::vector<double>& series_by_index(const Series& s, int i);
Series series(const Frames& raw);

struct Psd {
  std::vector<double> f, p;
};
// Hann-windowed periodogram averaged over 2-s half-overlapping segments.
Psd psd(const std::vector<double>& x, double fps);
// Fitted log-log PSD slope on 0.5 Hz .. min(Nyquist, 12 Hz); NaN if < 3 points.
double spectral_slope(const std::vector<double>& x, double fps);

struct SeriesStats {
  double mean, std, slope;
};
struct Stats {
  int frames = 0;
  double fps = 0;
  SeriesStats s[4];  // I, H, X, W
};
Stats stats(const Series& s, double fps);

// Log-spectral distance (dB) of power-normalised PSDs on a common band.
double lsd(const std::vector<double>& xa, double fa, const std::vector<double>& xb, double fb);
struct SeriesComparison {
  double lsd_db, std_ratio;  // std_ratio = std(B) / std(A)
};
struct Comparison {
  SeriesComparison s[4];
};
Comparison compare(const Series& a, double fa, const Series& b, double fb);

// Longest run of consecutive frames matching an earlier run (lag >= 2), seconds.
// Frames match when the mean abs difference of every 4th pixel in both directions is
// below frac x the median difference between consecutive frames.
double longest_repeat_s(const Frames& raw, double fps, double frac = 0.2);

// --- judging a clip against real ones ---
struct Measured {
  std::string dir;
  double fps = 0;
  Features features;
  Series series;
};
// Loads once, measures features and series.
Measured measure_clip(const std::string& dir, double fps, const LoadLimits& limits = {});

struct FeatureVerdict {
  std::string name;
  double real_min, real_max, value;
  bool inside;
  double source = NAN;  // the source clip's value, when judged by source
};
struct SpectrumVerdict {
  std::string series;
  std::vector<double> lsd_to_ref;     // the clip against each reference, dB
  std::vector<double> std_ratio;      // std(ref) / std(clip), per reference
  double real_min = 0, real_max = 0;  // over all pairs of references (needs >= 2)
  bool inside = false;                // every distance to a reference <= real_max
};
struct Judgement {
  std::vector<FeatureVerdict> features;
  std::vector<SpectrumVerdict> spectra;  // empty if not asked for
  int inside = 0, of = 0;                // over what was asked
};
// `names`: features to judge (empty = all); `spectra`: also the I/H/X/W distances.
// A series is inside when no real clip is further than the real clips are from
// each other, plus `spectra_margin_db` (0: the real-real spread itself; a
// margin lets a test hold progress towards the spread).
//
// `source` >= 0 judges a clip made from one of the references (a model of
// that footage, played back): a feature is also inside when it lies within
// `source_tolerance` (relative) of the source's own value (footage at the edge
// of the real range stays "as filmed" when its model lands just beyond it),
// and each series is judged by its distance to the source alone, against the
// real clips' spread.
struct SourceJudging {
  int source = -1;
  double tolerance = 0.1;
};
Judgement judge(const std::vector<Measured>& refs, const Measured& clip,
                const std::vector<std::string>& names, bool spectra, double spectra_margin_db = 0.0,
                const SourceJudging& by_source = {});

// The shared real clips of a kind: "candle" or "fire" (real speed). Empty if
// the kind is unknown. fps from the clips' table in ../shared/eval/README.md.
struct ClipRef {
  std::string name;
  double fps;
};
std::vector<ClipRef> clips_of_kind(const std::string& kind);
// A REFS file as flame_features.py judge reads it: lines "DIR FPS" (DIR may hold
// spaces; blank lines and # comments skipped; DIR as given, relative to the current
// folder). Throws ConfigError naming the line.
std::vector<ClipRef> read_refs_file(const std::string& path);

}  // namespace candela::measure
