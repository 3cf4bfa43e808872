#include "model_build.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "model/flame_model.h"
#include "render.h"

namespace candela::tools {

std::string tool_version() { return std::string("candela-tool ") + CANDELA_VERSION; }

namespace {

// Held-out single-plume frames rebuilt by both models with the same number of
// numbers per frame: E = np + nw + 1 + ne EigenFires versus the flame model.
void compare_equal_parameters(const Dataset& d, BuiltModel& m) {
  const LearningFlamesModel& lf = m.flames;
  m.equal_params = lf.dim();
  const int e = std::min(m.equal_params, m.pca.components());
  std::vector<int> pos(d.frames(), -1);
  for (size_t i = 0; i < lf.frames.size(); ++i) pos[lf.frames[i]] = static_cast<int>(i);
  double plain = 0, flames = 0;
  int n = 0;
  std::vector<float> out(d.frame_pixels());
  for (int f : m.holdout) {
    if (pos[f] < 0) continue;
    plain += m.pca.mse(f, e);
    lf.render(lf.params.row(pos[f]).transpose(), d.width, d.height, out.data());
    double s = 0;
    for (size_t p = 0; p < out.size(); ++p) {
      const double diff = std::clamp(out[p], 0.0f, 255.0f) - d.frame(f)[p];
      s += diff * diff;
    }
    flames += s / static_cast<double>(out.size());
    ++n;
  }
  if (n == 0) return;
  m.plain_equal_db = psnr_from_mse(plain / n);
  m.flames_equal_db = psnr_from_mse(flames / n);
}

}  // namespace

void check_build_options(const BuildOptions& opt) {
  if (opt.graph.max_successors + 1 > model::kMaxSuccessors)
    throw BuildOptionError("--successors " + std::to_string(opt.graph.max_successors) +
                           ": the graph player takes at most " +
                           std::to_string(model::kMaxSuccessors) +
                           " successors of a frame, the next frame and " +
                           std::to_string(model::kMaxSuccessors - 1) + " jumps");
  if (!opt.learning_flames) return;
  const ShapeOptions& so = opt.flames.shape;
  if (auto bad =
          model::learning_flames_size_problem(so.np, so.nw, opt.flames.ne, opt.flames.arp.order)) {
    const std::string what = bad->field.empty() ? "--np " + std::to_string(so.np) + ", --nw " +
                                                      std::to_string(so.nw) + ", --ne " +
                                                      std::to_string(opt.flames.ne)
                                                : "--" + bad->field;
    const std::string fix =
        bad->field.empty() ? "lower --np, --nw or --ne" : "change --" + bad->field;
    throw BuildOptionError("Learning Flames " + what + ": " + bad->problem + " (" + fix +
                           ", or build with --no-learning-flames)");
  }
}

BuiltModel build_model(const Dataset& d, const BuildOptions& opt) {
  check_build_options(opt);
  BuiltModel m;
  PcaOptions po = opt.pca;
  po.progress = opt.progress;
  if (opt.holdout_every > 1)
    for (int f = opt.holdout_every - 1; f < d.frames(); f += opt.holdout_every)
      m.holdout.push_back(f);
  po.holdout = m.holdout;
  m.pca = pca_snapshot(d, po);
  const int e = m.pca.components();
  for (int k = 1;; k *= 2) {
    const int kk = std::min(k, e);
    m.psnr.push_back({kk, psnr_over(m.pca, m.pca.train, kk),
                      m.holdout.empty() ? 0.0 : psnr_over(m.pca, m.holdout, kk)});
    if (kk == e) break;
  }
  if (opt.progress) opt.progress("motion graph over " + std::to_string(d.frames()) + " frames");
  WeightSpace space = WeightSpace::from(m.pca.weights, d.clips);
  m.graph = build_motion_graph(space, opt.graph);

  const int w = d.width, h = d.height, frames = d.frames();
  int single = 0;
  for (int f = 0; f < frames; ++f) single += !d.multi_plume[f];
  if (opt.learning_flames && single >= 16) {
    LearningFlamesOptions lo = opt.flames;
    lo.holdout = m.holdout;
    lo.progress = opt.progress;
    try {
      m.flames = learn_flames(d, lo);
      m.has_flames = true;
      compare_equal_parameters(d, m);
    } catch (const NoFlameSequence& e) {
      // A fire is mostly several plumes at once: its model is EigenFires and the graph.
      if (opt.progress) opt.progress(std::string("Learning Flames skipped: ") + e.what());
    }
  } else if (opt.learning_flames && opt.progress) {
    opt.progress("Learning Flames skipped: only " + std::to_string(single) +
                 " single-plume frames");
  }
  const size_t px = d.frame_pixels();
  // The black level: the runtime shows reconstructed gray at or below it as
  // black. Truncated PCA leaves a faint haze of positive values where no frame
  // has any flame, which would show as the model image's rectangle on a dark
  // screen: lift the level to the haze there (99.5th percentile over every
  // 4th frame, at the pixels black in all of them), at most to 24.
  float black_level = opt.colour.black_level;
  {
    std::vector<uint8_t> never(px, 1);
    for (int f = 0; f < frames; f += 4) {
      const uint8_t* src = d.frame(f);
      for (size_t p = 0; p < px; ++p) never[p] &= src[p] == 0;
    }
    std::vector<float> haze;
    Eigen::VectorXf rec;
    for (int f = 0; f < frames; f += 4) {
      rec = m.pca.mean + m.pca.basis * m.pca.weights.row(f).transpose();
      for (size_t p = 0; p < px; ++p)
        if (never[p]) haze.push_back(rec[static_cast<Eigen::Index>(p)]);
    }
    if (!haze.empty()) {
      const size_t at = haze.size() * 995 / 1000;
      std::nth_element(haze.begin(), haze.begin() + static_cast<ptrdiff_t>(at), haze.end());
      black_level = std::clamp(haze[at] + 1.0f, black_level, 24.0f);
    }
    m.black_level = black_level;
  }
  model::ModelWriter& mw = m.writer;
  nlohmann::json sources = nlohmann::json::array();
  for (const auto& c : d.clips) sources.push_back(c.source);
  nlohmann::json info = {{"kind", "eigenfires"},
                         {"width", w},
                         {"height", h},
                         {"components", e},
                         {"frames", frames},
                         {"intensity", "srgb"},
                         {"total_variance", m.pca.total_variance},
                         {"clips", clips_to_json(d.clips)},
                         {"multi_plume",
                          [&] {
                            nlohmann::json a = nlohmann::json::array();
                            for (int f = 0; f < frames; ++f)
                              if (d.multi_plume[f]) a.push_back(f);
                            return a;
                          }()},
                         {"graph",
                          {{"theta_min", m.graph.theta_min},
                           {"median_step", m.graph.median_step},
                           {"max_successors", opt.graph.max_successors},
                           {"min_jump", opt.graph.min_jump}}},
                         {"colour",
                          {{"hue", opt.colour.hue},
                           {"saturation", opt.colour.saturation},
                           {"glow_radius", opt.colour.glow_radius},
                           {"glow_strength", opt.colour.glow_strength},
                           {"black_level", black_level}}},
                         {"psnr",
                          [&] {
                            nlohmann::json a = nlohmann::json::array();
                            for (const auto& r : m.psnr)
                              a.push_back({{"components", r.components},
                                           {"train_db", r.train_db},
                                           {"holdout_db", r.holdout_db}});
                            return a;
                          }()},
                         {"provenance",
                          {{"tool", tool_version()},
                           {"sources", sources},
                           {"dataset_options", d.options},
                           {"options", opt.provenance_options}}}};
  mw.set_info(info);
  model::add_quantised(
      mw, "mean", model::quantise_images(m.pca.mean.data(), 1, px, model::DType::kU16), 1, w, h);
  Eigen::MatrixXf& basis = m.pca.basis;  // column k is eigen-image k
  model::add_quantised(mw, "eigen", model::quantise_images(basis.data(), e, px, opt.eigen_dtype), e,
                       w, h);
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> wr = m.pca.weights;
  mw.add_f32("weights", {frames, e}, {wr.data(), static_cast<size_t>(wr.size())});
  std::vector<float> var(e);
  for (int k = 0; k < e; ++k) var[k] = static_cast<float>(m.pca.variance[k]);
  mw.add_f32("variance", {e}, var);
  mw.add_i32("graph.offsets", {frames + 1}, m.graph.offsets);
  mw.add_i32("graph.successors", {static_cast<int64_t>(m.graph.successors.size())},
             m.graph.successors);
  mw.add_f32("graph.cost", {static_cast<int64_t>(m.graph.cost.size())}, m.graph.cost);
  // Without dynamics the part is kept for the comparison above but not
  // written: the runtime plays Learning Flames only through a learned ARP.
  if (m.has_flames && !opt.flames.learn_dynamics && opt.progress)
    opt.progress("Learning Flames without dynamics: compared, not written to the model");
  if (m.has_flames && opt.flames.learn_dynamics) {
    const LearningFlamesModel& lf = m.flames;
    const ShapeOptions& so = lf.shape;
    const int dim = lf.dim(), K = lf.dynamics.arp.order, T = static_cast<int>(lf.frames.size());
    const int ne = std::min(lf.ne, lf.appearance.components());
    const size_t npx = static_cast<size_t>(so.norm_width) * so.norm_height;
    info["learning_flames"] = {{"np", so.np},
                               {"nw", so.nw},
                               {"ne", lf.ne},
                               {"order", K},
                               {"width", so.norm_width},
                               {"height", so.norm_height},
                               {"frames", T},
                               {"base_y", so.base_row},
                               {"span", so.span},
                               {"arp_iterations", lf.dynamics.iterations},
                               {"arp_log_likelihood", lf.dynamics.log_likelihood},
                               {"holdout_psnr_equal_parameters",
                                {{"parameters", m.equal_params},
                                 {"eigenfires_db", m.plain_equal_db},
                                 {"learning_flames_db", m.flames_equal_db}}}};
    mw.set_info(info);
    model::add_quantised(
        mw, "lf.mean",
        model::quantise_images(lf.appearance.mean.data(), 1, npx, model::DType::kU16), 1,
        so.norm_width, so.norm_height);
    Eigen::MatrixXf eig = Eigen::MatrixXf::Zero(static_cast<Eigen::Index>(npx), lf.ne);
    eig.leftCols(ne) = lf.appearance.basis.leftCols(ne);
    model::add_quantised(mw, "lf.eigen",
                         model::quantise_images(eig.data(), lf.ne, npx, model::DType::kU16), lf.ne,
                         so.norm_width, so.norm_height);
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> pr =
        lf.params.cast<float>();
    mw.add_f32("lf.params", {T, dim}, {pr.data(), static_cast<size_t>(pr.size())});
    std::vector<float> A;
    for (int k = 0; k < K; ++k) {
      Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> ak =
          lf.dynamics.arp.A[k].cast<float>();
      A.insert(A.end(), ak.data(), ak.data() + ak.size());
    }
    mw.add_f32("arp.A", {K, dim, dim}, A);
    std::vector<float> dv(lf.dynamics.arp.d.data(), lf.dynamics.arp.d.data() + dim);
    mw.add_f32("arp.d", {dim}, dv);
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> b =
        lf.dynamics.arp.B.cast<float>();
    mw.add_f32("arp.B", {dim, dim}, {b.data(), static_cast<size_t>(b.size())});
  }
  // The runtime's own validation, on the very bytes `write` will store.
  try {
    (void)model::FlameModel::from(model::ModelFile::from_bytes(mw.bytes(), "the model built"));
  } catch (const model::ModelError& e) {
    throw std::runtime_error(std::string(e.what()) + " (the runtime would refuse this model)");
  }
  return m;
}

void write_reports(const Dataset& d, const BuiltModel& m, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const PcaResult& p = m.pca;
  {
    std::ofstream t(dir + "/psnr.txt");
    t << "# reconstruction PSNR (dB, peak 255) versus components E\n# E  train  holdout\n";
    for (const auto& r : m.psnr) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%4d  %6.2f  %6.2f\n", r.components, r.train_db, r.holdout_db);
      t << buf;
    }
  }
  {
    // PSNR versus log2(E): train in red, held-out in blue; axes with their
    // ticks and titles, a legend and a title.
    const int W = 560, H = 380, L = 64, R = 16, T = 40, B = 52;
    const std::array<uint8_t, 3> ink{0, 0, 0}, grid{220, 220, 220}, train{220, 50, 32},
        held{30, 120, 200};
    Canvas c(W, H);
    const std::string title = "Reconstruction PSNR vs components";
    c.text((W - Canvas::text_width(title, 2)) / 2, 10, title, ink, 2);
    double lo = 1e9, hi = -1e9;
    for (const auto& r : m.psnr)
      for (double db : {r.train_db, m.holdout.empty() ? r.train_db : r.holdout_db})
        if (std::isfinite(db)) lo = std::min(lo, db), hi = std::max(hi, db);  // exact: +inf
    if (lo > hi) lo = hi = 0;
    lo = std::floor(lo / 5) * 5;
    hi = std::clamp(std::ceil(hi / 5) * 5, lo + 5, lo + 200);
    const double xmax = std::log2(std::max(2, m.psnr.back().components));
    auto X = [&](int e) { return L + std::log2(e) / xmax * (W - L - R - 10); };
    auto Y = [&](double db) {
      db = std::isfinite(db) ? std::clamp(db, lo, hi) : hi;  // a perfect fit (+inf) at the top
      return (H - B) - (db - lo) / (hi - lo) * (H - B - T);
    };
    for (int db = static_cast<int>(lo); db <= hi + 1e-9; db += 5) {
      const int y = static_cast<int>(std::lround(Y(db)));
      if (db > lo) c.line(L + 1, y, W - R, y, grid);
      c.line(L - 5, y, L, y, ink);
      const std::string label = std::to_string(db);
      c.text(L - 8 - Canvas::text_width(label), y - 3, label, ink);
    }
    const std::string ytitle = "PSNR (dB, peak 255)";
    c.text_up(8, (H - B + T) / 2 + Canvas::text_width(ytitle) / 2, ytitle, ink);
    int last_label_end = -1000;
    for (const auto& r : m.psnr) {
      const int x = static_cast<int>(std::lround(X(r.components)));
      c.line(x, H - B, x, H - B + 5, ink);
      const std::string label = std::to_string(r.components);
      const int lx = x - Canvas::text_width(label) / 2;
      if (lx > last_label_end + 4) {  // crowded ticks (a long sweep): every other label
        c.text(lx, H - B + 9, label, ink);
        last_label_end = lx + Canvas::text_width(label);
      }
    }
    const std::string xtitle = "components E (log scale)";
    c.text((L + W - R - Canvas::text_width(xtitle)) / 2, H - 18, xtitle, ink);
    auto series = [&](auto value, std::array<uint8_t, 3> col) {
      for (size_t i = 0; i + 1 < m.psnr.size(); ++i)
        for (int d = 0; d < 2; ++d)  // two pixels thick
          c.line(X(m.psnr[i].components), Y(value(m.psnr[i])) + d, X(m.psnr[i + 1].components),
                 Y(value(m.psnr[i + 1])) + d, col);
      for (const auto& r : m.psnr) {
        const int x = static_cast<int>(std::lround(X(r.components)));
        const int y = static_cast<int>(std::lround(Y(value(r))));
        c.rect(x - 2, y - 2, x + 3, y + 3, col);
      }
    };
    series([](const PsnrRow& r) { return r.train_db; }, train);
    if (!m.holdout.empty()) series([](const PsnrRow& r) { return r.holdout_db; }, held);
    c.line(L, T - 6, L, H - B, ink);
    c.line(L, H - B, W - R, H - B, ink);
    // The legend, bottom right inside the plot (PSNR rises to the right).
    const std::vector<std::pair<std::string, std::array<uint8_t, 3>>> entries =
        m.holdout.empty()
            ? std::vector<std::pair<std::string, std::array<uint8_t, 3>>>{{"train", train}}
            : std::vector<std::pair<std::string, std::array<uint8_t, 3>>>{
                  {"train", train}, {"held-out frames", held}};
    const int lw = 14 + 6 + Canvas::text_width("held-out frames") + 12,
              lh = 8 + 14 * static_cast<int>(entries.size());
    const int lx = W - R - lw - 8, ly = H - B - lh - 8;
    c.rect(lx, ly, lx + lw, ly + lh, {150, 150, 150});
    c.rect(lx + 1, ly + 1, lx + lw - 1, ly + lh - 1, {255, 255, 255});
    for (size_t i = 0; i < entries.size(); ++i) {
      const int ey = ly + 5 + 14 * static_cast<int>(i);
      c.rect(lx + 6, ey, lx + 20, ey + 8, entries[i].second);
      c.text(lx + 26, ey, entries[i].first, ink);
    }
    write_png(dir + "/psnr.png", c.img);
  }
  {
    // Contact sheet: the mean, then eigen-images (mid-gray = 0), each with its
    // component number above it (the studio's w0, w1, ...), under a title.
    const int cols = 6, show = std::min(p.components(), 17);
    const int w = p.width, h = p.height, rows = (show + 1 + cols - 1) / cols;
    const int zoom = std::max(1, (40 + w - 1) / w);  // small models drawn larger
    const int cw = w * zoom + 4, ch = h * zoom + 14, top = 24;
    const std::string title =
        "Mean and eigen-images 0-" + std::to_string(show - 1) + " (mid-gray = 0)";
    const int sheet_w = std::max(cols * cw, Canvas::text_width(title) + 8);
    Canvas c(sheet_w, top + rows * ch, {0, 0, 0});
    c.text(4, 8, title, {255, 255, 255});
    for (int i = 0; i <= show; ++i) {
      const int ox = (i % cols) * cw + 2, oy = top + (i / cols) * ch;
      c.text(ox, oy + 2, i == 0 ? std::string("mean") : std::to_string(i - 1), {255, 220, 120});
      const float peak = i == 0 ? 1.0f : p.basis.col(i - 1).cwiseAbs().maxCoeff();
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t at = static_cast<size_t>(y) * w + x;
          const float v = i == 0 ? p.mean[at]
                                 : 127.5f + 127.5f * p.basis(static_cast<Eigen::Index>(at), i - 1) /
                                                std::max(peak, 1e-12f);
          const auto g = static_cast<uint8_t>(std::clamp(std::lround(v), 0l, 255l));
          c.rect(ox + x * zoom, oy + 11 + y * zoom, ox + (x + 1) * zoom, oy + 11 + (y + 1) * zoom,
                 {g, g, g});
        }
    }
    write_png(dir + "/eigenfires.png", c.img);
  }
  if (p.components() >= 3) {
    // The first three weights from three viewpoints (oblique, from above,
    // from the front), one colour per clip, the axes w0 red, w1 green, w2
    // blue and named at their tips; a legend of the clips and a title.
    const int S = 400, top = 30;
    const std::array<uint8_t, 3> ink{0, 0, 0};
    double scale = 0;
    for (int k = 0; k < 3; ++k)
      scale = std::max<double>(scale, p.weights.col(k).cwiseAbs().maxCoeff());
    scale = std::max(scale, 1e-12);
    // The legend's rows: a swatch and the clip's name each, wrapped to the width.
    const int W = 3 * S;
    std::vector<std::pair<int, int>> at_of(d.clips.size());
    int lx = 10, ly = top + S + 12;
    for (size_t i = 0; i < d.clips.size(); ++i) {
      const int ew = 20 + Canvas::text_width(d.clips[i].name) + 18;
      if (lx > 10 && lx + ew > W - 10) lx = 10, ly += 16;
      at_of[i] = {lx, ly};
      lx += ew;
    }
    Canvas c(W, ly + 22);
    const std::string title = "First three weights (w0, w1, w2): one track per clip";
    c.text((W - Canvas::text_width(title, 2)) / 2, 8, title, ink, 2);
    struct View {
      const char* name;
      double yaw, pitch;
    };
    const View views[3] = {{"oblique", 0.6, 0.45},
                           {"from above: w0 right, w1 up", 0.0, 1.5707963},
                           {"from the front: w0 right, w2 up", 0.0, 0.0}};
    const std::array<uint8_t, 3> axis[3] = {{255, 0, 0}, {0, 180, 0}, {0, 0, 255}};
    for (int v = 0; v < 3; ++v) {
      const int ox = v * S;
      const double yaw = views[v].yaw, pitch = views[v].pitch;
      auto proj = [&](double a, double b, double z) {
        const double x1 = a * std::cos(yaw) - b * std::sin(yaw);
        const double y1 = a * std::sin(yaw) + b * std::cos(yaw);
        const double y2 = y1 * std::sin(pitch) + z * std::cos(pitch);
        return std::pair<double, double>{ox + S / 2 + 0.4 * S * x1 / scale,
                                         top + S / 2 - 0.4 * S * y2 / scale};
      };
      c.rect(ox + 4, top, ox + S - 4, top + 1, {200, 200, 200});
      c.rect(ox + 4, top + S - 1, ox + S - 4, top + S, {200, 200, 200});
      c.rect(ox + 4, top, ox + 5, top + S, {200, 200, 200});
      c.rect(ox + S - 5, top, ox + S - 4, top + S, {200, 200, 200});
      c.text(ox + 10, top + 6, views[v].name, ink);
      for (int f = 0; f + 1 < d.frames(); ++f) {
        const int clip = [&] {
          for (size_t i = 0; i < d.clips.size(); ++i)
            if (f >= d.clips[i].first && f < d.clips[i].first + d.clips[i].count)
              return static_cast<int>(i);
          return 0;
        }();
        if (f + 1 >= d.clips[clip].first + d.clips[clip].count) continue;
        auto [x0, y0] = proj(p.weights(f, 0), p.weights(f, 1), p.weights(f, 2));
        auto [x1, y1] = proj(p.weights(f + 1, 0), p.weights(f + 1, 1), p.weights(f + 1, 2));
        c.line(x0, y0, x1, y1, palette(clip + 3));
      }
      for (int k = 0; k < 3; ++k) {
        double e[3] = {0, 0, 0};
        e[k] = scale;
        auto [x0, y0] = proj(0, 0, 0);
        auto [x1, y1] = proj(e[0], e[1], e[2]);
        c.line(x0, y0, x1, y1, axis[k]);
        if (std::hypot(x1 - x0, y1 - y0) > 12) {  // an axis seen end-on is not named
          const std::string name = "w" + std::to_string(k);
          const double len = std::hypot(x1 - x0, y1 - y0);
          c.text(static_cast<int>(x1 + 9 * (x1 - x0) / len) - 5,
                 static_cast<int>(y1 + 9 * (y1 - y0) / len) - 3, name, axis[k]);
        }
      }
    }
    for (size_t i = 0; i < d.clips.size(); ++i) {
      const auto [x, y] = at_of[i];
      c.rect(x, y, x + 14, y + 8, palette(static_cast<int>(i) + 3));
      c.text(x + 20, y, d.clips[i].name, ink);
    }
    write_png(dir + "/trajectory.png", c.img);
  }
}

}  // namespace candela::tools
