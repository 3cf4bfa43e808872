#include "flame_view.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "elements/eigenflame/eigen_renderer.h"
#include "elements/eigenflame/eigenflame.h"
#include "gl/math.h"
#include "model/flame_model.h"

namespace candela::studio {
namespace {

Mat4 ortho(float l, float r, float b, float t) {
  Mat4 m;
  m.m[0] = 2 / (r - l);
  m.m[5] = 2 / (t - b);
  m.m[10] = -1.0f / 10;  // z in [-10, 10]
  m.m[12] = -(r + l) / (r - l);
  m.m[13] = -(t + b) / (t - b);
  return m;
}

constexpr float kPad = 0.15f;  // room for the glow around the image, image heights

}  // namespace

FlameView::FlameView(const EigenModel& model)
    : model_(model), weights_(static_cast<size_t>(model.model->components()), 0.0f) {}

FlameView::~FlameView() = default;

void FlameView::render(std::span<const float> weights, const Look& look, int w, int h) {
  const model::FlameModel& m = *model_.model;
  w = std::max(w, 16);
  h = std::max(h, 16);
  // Nothing changed (paused, or a model frame held between two UI frames):
  // the texture already shows it.
  const size_t n = std::min(weights.size(), weights_.size());
  const bool same_weights =
      std::equal(weights.begin(), weights.begin() + static_cast<ptrdiff_t>(n), weights_.begin()) &&
      std::all_of(weights_.begin() + static_cast<ptrdiff_t>(n), weights_.end(),
                  [](float v) { return v == 0; });
  if (renderer_ && have_look_ && look == look_ && w == w_ && h == h_ && same_weights) return;
  if (!renderer_ || !have_look_ || !(look == look_)) {
    FlameLookSettings s;
    if (look.transfer.size() >= 2) {
      std::vector<Vec3> stops;
      for (const auto& c : look.transfer) stops.push_back({c[0], c[1], c[2]});
      // Evenly spaced: the element's plain `transfer` (the very same ramp).
      std::vector<float> at;
      if (!look.evenly_spaced()) at = look.transfer_at;
      s.ramp = transfer_ramp(stops, m.colour.black_level, at);
    } else {
      s.ramp = hls_ramp(look.hue, look.saturation, m.colour.black_level,
                        look.has_hue_top ? look.hue_top : look.hue);
    }
    s.brightness = look.brightness;
    s.glow_radius = std::max(0.02f, look.glow_radius);  // as the element clamps the model's
    s.glow_strength = look.glow_strength;
    renderer_.reset();  // first: the shared batch is laid out afresh for the new one
    renderer_ = std::make_unique<EigenRenderer>(image_stack_of(m.mean), image_stack_of(m.eigen),
                                                StackLayout::kPacked,
                                                EigenReconstructor::kMaxComponents, s, weights_);
    look_ = look;
    have_look_ = true;
  }
  if (w != w_ || h != h_) {
    target_ = RenderTarget::checked(w, h, "studio: the flame view");
    w_ = w;
    h_ = h;
  }
  std::copy_n(weights.begin(), n, weights_.begin());
  std::fill(weights_.begin() + static_cast<ptrdiff_t>(n), weights_.end(), 0.0f);

  // The image (aspect a, height 1, bottom centre at the origin) and its glow
  // margin, fitted into the view keeping the aspect.
  const float a = static_cast<float>(m.width()) / m.height();
  float half_w = a / 2 + kPad, lo = -kPad, hi = 1 + kPad;
  const float view_aspect = static_cast<float>(w) / h;
  if (2 * half_w / (hi - lo) < view_aspect) {
    half_w = (hi - lo) * view_aspect / 2;
  } else {
    const float extra = (2 * half_w / view_aspect - (hi - lo)) / 2;
    lo -= extra;
    hi += extra;
  }
  const float px = w / (2 * half_w);  // pixels per image height
  image_ = {static_cast<int>(std::lround((half_w - a / 2) * px)),
            static_cast<int>(std::lround((hi - 1) * px)), static_cast<int>(std::lround(a * px)),
            static_cast<int>(std::lround(px))};

  target_.bind();
  glViewport(0, 0, w, h);
  glClearColor(0, 0, 0, 1);  // alpha stays 1 under the additive flame: the UI shows it opaque
  glClear(GL_COLOR_BUFFER_BIT);
  renderer_->prepare();  // offscreen; restores our framebuffer and viewport
  FlamePose pose;
  pose.origin = {0, 0, 0};
  pose.height = 1;
  const Mat4 view = Mat4::identity();
  renderer_->composite(view, ortho(-half_w, half_w, lo, hi) * view, pose);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace candela::studio
