#include "elements/test_pattern/test_pattern.h"

#include <array>
#include <cmath>
#include <cstdint>

#include "gl/program.h"
#include "gl/texture.h"
#include "params/params.h"

namespace candela {
namespace {

// The frame counter's eight digits (frames modulo 10^8, leading zeros shown)
// as seven-segment masks, segments a..g as bits 0..6.
std::array<int, 8> counter_segments(uint64_t frame) {
  static constexpr int kMask[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F};
  std::array<int, 8> out{};
  for (int i = 7; i >= 0; --i, frame /= 10) out[static_cast<size_t>(i)] = kMask[frame % 10];
  return out;
}

// Pixels [lo, hi) along one axis.
struct Span {
  int lo = 0, hi = 0;
  bool empty() const { return hi <= lo; }
};

// The pixels of 0..n-1 whose centre c (i + 0.5, in float as a fragment
// shader sees it) satisfies `inside`, taken as one run (every region below
// is convex along the axis).
template <typename Inside>
Span span_where(int n, Inside inside) {
  Span s{n, n};
  for (int i = 0; i < n; ++i)
    if (inside(static_cast<float>(i) + 0.5f)) {
      if (s.lo == n) s.lo = i;
      s.hi = i + 1;
    }
  if (s.lo == n) s = {};
  return s;
}

constexpr float kSegment = 0.14f;  // a segment's thickness, of a digit's width

// The pattern at one screen size, in pixels with y down from the top:
// colour bars (top two thirds), a counter band of eight seven-segment digits,
// a grey marker band (its marker placed per frame) and a one-pixel white
// border. Worked out once per size with the arithmetic of a per-pixel
// shader, so a pixel is lit where that shader lit it; drawn as flat
// rectangles, which a software GPU fills at several times the speed of a
// shader that decides every pixel.
struct Layout {
  int width = 0, height = 0;
  Span bar_rows, counter_rows, marker_rows;
  std::array<Span, 8> bar_columns;
  // Per digit cell: its left, middle and right columns (segments f/e, a/g/d, b/c).
  std::array<std::array<Span, 3>, 8> digit_columns;
  // Rows of segment a, the top half (b, f), the bottom half (c, e), d and g.
  Span a_rows, top_rows, bottom_rows, d_rows, g_rows;
  Span marker_band_rows;  // the marker square's rows
  float marker_side = 0;

  Layout() = default;
  Layout(int w, int h) : width(w), height(h) {
    const float W = static_cast<float>(w), H = static_cast<float>(h);
    bar_rows = span_where(h, [&](float y) { return y / H < 2.0f / 3.0f; });
    counter_rows =
        span_where(h, [&](float y) { return !(y / H < 2.0f / 3.0f) && y / H < 5.0f / 6.0f; });
    marker_rows = span_where(h, [&](float y) { return !(y / H < 5.0f / 6.0f); });
    for (int i = 0; i < 8; ++i)
      bar_columns[static_cast<size_t>(i)] = span_where(w, [&](float x) {
        const int bar = static_cast<int>(x / W * 8.0f);
        return (bar < 0 ? 0 : bar > 7 ? 7 : bar) == i;
      });
    // The counter: cells 0.7 of the band high, 0.55 as wide, 1.3 widths apart,
    // inset 0.15 of the band from its left and top.
    const float band = H / 6.0f, ch = band * 0.7f, cw = ch * 0.55f, pitch = cw * 1.3f;
    for (int c = 0; c < 8; ++c) {
      const auto in_cell = [&, c](float x, float lo, float hi, bool lo_open, bool hi_open) {
        const float q = x - band * 0.15f;
        if (static_cast<int>(std::floor(q / pitch)) != c) return false;
        const float local = (q - pitch * std::floor(q / pitch)) / cw;
        if (!(local <= 1.0f)) return false;
        return (lo_open ? local > lo : local >= lo) && (hi_open ? local < hi : local <= hi);
      };
      auto& cols = digit_columns[static_cast<size_t>(c)];
      cols[0] = span_where(w, [&](float x) { return in_cell(x, -1.0f, kSegment, false, false); });
      cols[1] =
          span_where(w, [&](float x) { return in_cell(x, kSegment, 1.0f - kSegment, true, true); });
      cols[2] =
          span_where(w, [&](float x) { return in_cell(x, 1.0f - kSegment, 2.0f, false, false); });
    }
    const auto local_y = [&](float y) { return (y - H * 2.0f / 3.0f - band * 0.15f) / ch; };
    const auto in_digit = [&](float y) { return local_y(y) >= 0.0f && local_y(y) <= 1.0f; };
    a_rows = span_where(h, [&](float y) { return in_digit(y) && local_y(y) < kSegment; });
    top_rows = span_where(h, [&](float y) { return in_digit(y) && local_y(y) < 0.5f; });
    bottom_rows = span_where(h, [&](float y) { return in_digit(y) && local_y(y) >= 0.5f; });
    d_rows = span_where(h, [&](float y) { return in_digit(y) && local_y(y) > 1.0f - kSegment; });
    g_rows = span_where(
        h, [&](float y) { return in_digit(y) && std::abs(local_y(y) - 0.5f) < kSegment * 0.5f; });
    // The marker: a square 0.8 of its band, 0.1 of the band from its top.
    marker_side = band * 0.8f;
    const float y0 = H * 5.0f / 6.0f + band * 0.1f;
    marker_band_rows = span_where(h, [&](float y) { return y >= y0 && y < y0 + marker_side; });
  }
};

constexpr int kMaxRects = 8 + 1 + 8 * 7 + 1 + 1 + 4;
constexpr int kFloatsPerVertex = 5;  // x, y (normalised device coordinates), r, g, b
constexpr int kFloatsPerRect = 6 * kFloatsPerVertex;

class TestPattern final : public Element {
 public:
  explicit TestPattern(int steps_per_period)
      : steps_per_period_(steps_per_period),
        program_(Program::from_library("test_pattern.vert", "test_pattern.frag")),
        vao_(make_vertex_array()),
        vbo_(make_buffer()) {
    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, vbo_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(sizeof(vertices_)), nullptr,
                 GL_STREAM_DRAW);
    const auto stride = static_cast<GLsizei>(kFloatsPerVertex * sizeof(float));
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(2 * sizeof(float)));
    glBindVertexArray(0);
  }

  void update(const StepContext& s) override {
    phase_ = test_pattern_phase(s.step, steps_per_period_);
  }
  void hash_state(StateHash& hash) const override { hash.add(phase_); }

  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass != DrawPass::kBackground || f.width <= 0 || f.height <= 0) return;
    if (layout_.width != f.width || layout_.height != f.height) layout_ = Layout(f.width, f.height);
    const Layout& l = layout_;
    rects_ = 0;
    // Later rectangles cover earlier ones (one draw keeps their order).
    static constexpr float kBars[8][3] = {{1, 1, 1}, {1, 1, 0}, {0, 1, 1}, {0, 1, 0},
                                          {1, 0, 1}, {1, 0, 0}, {0, 0, 1}, {0, 0, 0}};
    for (size_t i = 0; i < 8; ++i) add(l.bar_columns[i], l.bar_rows, kBars[i]);
    static constexpr float kBlack[3] = {0, 0, 0}, kWhite[3] = {1, 1, 1},
                           kGrey[3] = {0.25f, 0.25f, 0.25f};
    const Span all_columns{0, l.width};
    add(all_columns, l.counter_rows, kBlack);
    const std::array<int, 8> digits = counter_segments(f.frame);
    for (size_t c = 0; c < 8; ++c) {
      const int m = digits[c];
      const auto& cols = l.digit_columns[c];
      if (m & 0x01) add(cols[1], l.a_rows, kWhite);
      if (m & 0x02) add(cols[2], l.top_rows, kWhite);
      if (m & 0x04) add(cols[2], l.bottom_rows, kWhite);
      if (m & 0x08) add(cols[1], l.d_rows, kWhite);
      if (m & 0x10) add(cols[0], l.bottom_rows, kWhite);
      if (m & 0x20) add(cols[0], l.top_rows, kWhite);
      if (m & 0x40) add(cols[1], l.g_rows, kWhite);
    }
    add(all_columns, l.marker_rows, kGrey);
    // The marker's left edge at phase of its travel, as the pixels whose centre is in it.
    const float x0 = static_cast<float>(phase_) * (static_cast<float>(l.width) - l.marker_side);
    add(span_where(l.width, [&](float x) { return x >= x0 && x < x0 + l.marker_side; }),
        l.marker_band_rows, kWhite);
    // A one-pixel white border shows the mode's true edges.
    const Span all_rows{0, l.height};
    add({0, 1}, all_rows, kWhite);
    add({l.width - 1, l.width}, all_rows, kWhite);
    add(all_columns, {0, 1}, kWhite);
    add(all_columns, {l.height - 1, l.height}, kWhite);

    program_.use();
    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, vbo_.get());
    glBufferSubData(GL_ARRAY_BUFFER, 0,
                    static_cast<GLsizeiptr>(rects_ * kFloatsPerRect * sizeof(float)),
                    vertices_.data());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDrawArrays(GL_TRIANGLES, 0, rects_ * 6);
    glBindVertexArray(0);
  }

 private:
  // Appends the rectangle of columns x, rows y (from the top) as two triangles.
  void add(Span x, Span y, const float (&rgb)[3]) {
    if (x.empty() || y.empty() || rects_ >= kMaxRects) return;
    const float w = static_cast<float>(layout_.width), h = static_cast<float>(layout_.height);
    const float x0 = 2.0f * x.lo / w - 1.0f, x1 = 2.0f * x.hi / w - 1.0f;
    const float y0 = 1.0f - 2.0f * y.hi / h, y1 = 1.0f - 2.0f * y.lo / h;  // y up
    const float corners[6][2] = {{x0, y0}, {x1, y0}, {x0, y1}, {x0, y1}, {x1, y0}, {x1, y1}};
    float* v = vertices_.data() + static_cast<size_t>(rects_) * kFloatsPerRect;
    for (const auto& c : corners) {
      *v++ = c[0];
      *v++ = c[1];
      *v++ = rgb[0];
      *v++ = rgb[1];
      *v++ = rgb[2];
    }
    ++rects_;
  }

  int steps_per_period_;
  double phase_ = 0;
  Program program_;
  VertexArray vao_;
  Buffer vbo_;
  Layout layout_;
  std::array<float, kMaxRects * kFloatsPerRect> vertices_{};
  int rects_ = 0;
};

class TestPatternSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext&) const override {
    return std::make_unique<TestPattern>(steps_per_period);
  }
  int steps_per_period = 120;
};

std::unique_ptr<ElementSpec> parse(ParamReader& r) {
  auto spec = std::make_unique<TestPatternSpec>();
  spec->steps_per_period = static_cast<int>(r.integer("period_steps", 120, 2, 1000000));
  r.finish();
  return spec;
}

}  // namespace

const ElementKind& test_pattern_kind() {
  static const ElementKind kind{"test_pattern", "colour bars, frame counter and a moving marker",
                                parse};
  return kind;
}

}  // namespace candela
