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
    // PSNR versus log2(E): train in red, held-out in blue.
    const int W = 480, H = 320, L = 40, B = 30;
    Canvas c(W, H);
    c.line(L, H - B, W - 10, H - B, {0, 0, 0});
    c.line(L, 10, L, H - B, {0, 0, 0});
    double lo = 1e9, hi = -1e9;
    for (const auto& r : m.psnr) {
      lo = std::min({lo, r.train_db, m.holdout.empty() ? r.train_db : r.holdout_db});
      hi = std::max({hi, r.train_db, r.holdout_db});
    }
    lo = std::floor(lo / 5) * 5;
    hi = std::ceil(hi / 5) * 5 + 1e-9;
    for (double db = lo; db <= hi; db += 5) {
      const double y = (H - B) - (db - lo) / (hi - lo) * (H - B - 10);
      c.line(L - 5, y, W - 10, y, {220, 220, 220});
    }
    const double xmax = std::log2(std::max(2, m.psnr.back().components));
    auto X = [&](int e) { return L + std::log2(e) / xmax * (W - L - 20); };
    auto Y = [&](double db) { return (H - B) - (db - lo) / (hi - lo) * (H - B - 10); };
    for (size_t i = 0; i + 1 < m.psnr.size(); ++i) {
      c.line(X(m.psnr[i].components), Y(m.psnr[i].train_db), X(m.psnr[i + 1].components),
             Y(m.psnr[i + 1].train_db), {220, 50, 32});
      if (!m.holdout.empty())
        c.line(X(m.psnr[i].components), Y(m.psnr[i].holdout_db), X(m.psnr[i + 1].components),
               Y(m.psnr[i + 1].holdout_db), {30, 120, 200});
    }
    for (const auto& r : m.psnr)
      c.rect(static_cast<int>(X(r.components)) - 2, H - B, static_cast<int>(X(r.components)) + 2,
             H - B + 6, {0, 0, 0});
    write_png(dir + "/psnr.png", c.img);
  }
  {
    // Contact sheet: the mean, then eigen-images (mid-gray = 0).
    const int cols = 6, show = std::min(p.components(), 17);
    const int w = p.width, h = p.height, rows = (show + 1 + cols - 1) / cols;
    Canvas c(cols * (w + 2), rows * (h + 2), {0, 0, 0});
    for (int i = 0; i <= show; ++i) {
      const int ox = (i % cols) * (w + 2), oy = (i / cols) * (h + 2);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t at = static_cast<size_t>(y) * w + x;
          float v;
          if (i == 0) {
            v = p.mean[at];
          } else {
            const float peak = p.basis.col(i - 1).cwiseAbs().maxCoeff();
            v = 127.5f +
                127.5f * p.basis(static_cast<Eigen::Index>(at), i - 1) / std::max(peak, 1e-12f);
          }
          const auto g = static_cast<uint8_t>(std::clamp(std::lround(v), 0l, 255l));
          c.dot(ox + x, oy + y, {g, g, g});
        }
    }
    write_png(dir + "/eigenfires.png", c.img);
  }
  if (p.components() >= 3) {
    // First three weights, fixed oblique view, one colour per clip; axes red/green/blue.
    const int S = 480;
    Canvas c(S, S);
    const double yaw = 0.6, pitch = 0.45;
    double scale = 0;
    for (int k = 0; k < 3; ++k)
      scale = std::max<double>(scale, p.weights.col(k).cwiseAbs().maxCoeff());
    auto proj = [&](double a, double b, double z) {
      const double x1 = a * std::cos(yaw) - b * std::sin(yaw);
      const double y1 = a * std::sin(yaw) + b * std::cos(yaw);
      const double y2 = y1 * std::sin(pitch) + z * std::cos(pitch);
      return std::pair<double, double>{S / 2 + 0.42 * S * x1 / scale,
                                       S / 2 - 0.42 * S * y2 / scale};
    };
    const std::array<uint8_t, 3> axis[3] = {{255, 0, 0}, {0, 180, 0}, {0, 0, 255}};
    for (int k = 0; k < 3; ++k) {
      double v[3] = {0, 0, 0};
      v[k] = scale;
      auto [x0, y0] = proj(0, 0, 0);
      auto [x1, y1] = proj(v[0], v[1], v[2]);
      c.line(x0, y0, x1, y1, axis[k]);
    }
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
    write_png(dir + "/trajectory.png", c.img);
  }
}

}  // namespace candela::tools
