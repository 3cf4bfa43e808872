// EigenFires PCA against numpy's SVD on a real clip, and held-out
// reconstruction PSNR on the real clips.
#include "pca.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "model_build.h"
#include "model_test_support.h"
#include "support/temp_dir.h"

namespace ct = candela::tools;

TEST(Pca, MatchesNumpySvdOnARealClip) {
  // The calm candle, 60 frames at 48x80: 3840-dimensional points.
  ct::Dataset d = ct::test::small_dataset("candle_schodl_singan", 48, 80, 4);
  ASSERT_EQ(d.frames(), 60);
  const int k = 8;
  ct::PcaOptions o;
  o.components = k;
  ct::PcaResult r = ct::pca_snapshot(d, o);
  ASSERT_EQ(r.components(), k);

  const candela::test::TempDir tmp("candela_pca_test_");
  const std::string& dir = tmp.path();
  {
    std::ofstream f(dir + "/frames.u8", std::ios::binary);
    f.write(reinterpret_cast<const char*>(d.pixels.data()),
            static_cast<std::streamsize>(d.pixels.size()));
  }
  const std::string cmd =
      "/usr/bin/python3 " + std::string(CANDELA_SOURCE_DIR) + "/tests/tools/model/pca_reference.py " +
      dir + "/frames.u8 " + std::to_string(d.frames()) + " " + std::to_string(d.height) + " " +
      std::to_string(d.width) + " " + std::to_string(k) + " " + dir + "/ref.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(dir + "/ref.txt");
  std::string line;
  std::getline(in, line);
  std::istringstream vs(line);
  const Eigen::Index n = r.mean.size();
  Eigen::MatrixXd ref(n, k);
  for (int i = 0; i < k; ++i) {
    double v;
    vs >> v;
    EXPECT_NEAR(r.variance[i], v, 1e-4 * v) << "variance of component " << i;
  }
  for (int i = 0; i < k; ++i)
    for (Eigen::Index p = 0; p < n; ++p) in >> ref(p, i);
  ASSERT_TRUE(in) << "reference output incomplete";
  // Same principal subspace: cosines of the principal angles between the
  // first j directions are 1 for every j (each direction sign-free).
  for (int j = 1; j <= k; ++j) {
    Eigen::MatrixXd c = r.basis.leftCols(j).cast<double>().transpose() * ref.leftCols(j);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(c);
    EXPECT_GT(svd.singularValues().minCoeff(), 1.0 - 1e-4) << "subspace of the first " << j;
    EXPECT_NEAR(std::abs(c(j - 1, j - 1)), 1.0, 1e-4) << "direction " << j - 1;
  }
}

TEST(Pca, HeldOutFramesReconstructWellOnRealClips) {
  // Every 10th frame left out of the fit, then projected and rebuilt.
  struct Case {
    const char* clip;
    double min_db_at_16;
  };
  for (const Case& c :
       {Case{"candle_schodl_singan", 30.0}, Case{"candle_breeze_tfg_flameshaken", 21.0}}) {
    ct::Dataset d = ct::test::small_dataset(c.clip, 48, 80, 1);
    ct::BuildOptions o;
    o.pca.components = 32;
    o.learning_flames = false;  // EigenFires only here
    ct::BuiltModel m = ct::build_model(d, o);
    ASSERT_FALSE(m.holdout.empty());
    double last = 0;
    for (const auto& row : m.psnr) {
      std::printf("%s: E=%d train %.2f dB, held-out %.2f dB\n", c.clip, row.components,
                  row.train_db, row.holdout_db);
      EXPECT_GE(row.holdout_db, last - 1e-9) << "PSNR must not fall as E grows";
      EXPECT_LE(row.holdout_db, row.train_db + 0.5) << "held-out frames are not fitted";
      last = row.holdout_db;
      if (row.components == 16) {
        EXPECT_GT(row.holdout_db, c.min_db_at_16) << c.clip;
      }
    }
  }
}

TEST(Pca, HeldOutProjectionIsTheLeastSquaresFit) {
  // A held-out frame's weights are basis^T (frame - mean); rebuilding from them
  // gives exactly the MSE the PSNR table uses.
  ct::Dataset d = ct::test::small_dataset("candle_breeze_tfg_flameshaken", 32, 48, 3);
  ct::PcaOptions o;
  o.components = 6;
  o.holdout = {5, 17};
  ct::PcaResult r = ct::pca_snapshot(d, o);
  for (int f : o.holdout) {
    Eigen::VectorXf x(r.mean.size());
    for (Eigen::Index p = 0; p < x.size(); ++p) x[p] = d.frame(f)[p];
    Eigen::VectorXf rec = r.mean + r.basis * r.weights.row(f).transpose();
    const double mse = (x - rec).squaredNorm() / static_cast<double>(x.size());
    EXPECT_NEAR(mse, r.mse(f, 6), 1e-3 * mse + 1e-6);
  }
}

TEST(Pca, AsManyComponentsAsAskedPastTheVarianceCap) {
  // `build --components N` is a user's exact request: a model of a 500-frame
  // clip asked for 499 EigenFires got 128 (max_components, the cap meant for
  // --variance), and played back visibly blurred. --variance stays capped.
  // 150 frames of 24x24 noise, centred: they span 149 dimensions.
  const int w = 24, h = 24, frames = 150;
  std::vector<uint8_t> px(static_cast<size_t>(w) * h * frames);
  uint32_t state = 99;
  for (auto& v : px) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(state >> 24);
  }
  ct::PcaOptions o;
  o.components = 140;  // above max_components (128 by default)
  ASSERT_LT(o.max_components, o.components);
  EXPECT_EQ(ct::pca_snapshot(px.data(), w, h, frames, o).components(), 140);
  o.components = 0;
  o.variance = 0.999;  // would need about 149
  EXPECT_EQ(ct::pca_snapshot(px.data(), w, h, frames, o).components(), o.max_components);
  o.components = 400;  // more than the frames span: all they span
  EXPECT_EQ(ct::pca_snapshot(px.data(), w, h, frames, o).components(), frames - 1);
}

TEST(Pca, FramesThatDoNotVaryAreRefusedSayingSo) {
  // 30 black frames: no component to learn (it built a model of noise, or
  // failed later naming model.components).
  std::vector<uint8_t> px(static_cast<size_t>(16) * 16 * 30, 0);
  ct::PcaOptions o;
  o.components = 4;
  try {
    ct::pca_snapshot(px.data(), 16, 16, 30, o);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nothing varies"), std::string::npos) << e.what();
  }
}

#ifdef _OPENMP
TEST(Pca, SameBytesOnAnyNumberOfThreads) {
  // A model is an asset that goes into the repository: building it again from
  // the same dataset must give the same file, whatever the machine's cores.
  // 40 frames of 64x96 (six pixel blocks), made up of moving blobs and noise.
  const int w = 64, h = 96, frames = 40;
  std::vector<uint8_t> px(static_cast<size_t>(w) * h * frames);
  uint32_t state = 12345;
  for (int f = 0; f < frames; ++f)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        state = state * 1664525u + 1013904223u;
        const double dx = x - 32 - 8 * std::sin(f * 0.3), dy = y - 60 + 20 * std::cos(f * 0.2);
        const double v = 200 * std::exp(-(dx * dx + dy * dy) / 300.0) + (state >> 27);
        px[(static_cast<size_t>(f) * h + y) * w + x] = static_cast<uint8_t>(std::min(255.0, v));
      }
  ct::PcaOptions o;
  o.components = 12;
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    return ct::pca_snapshot(px.data(), w, h, frames, o);
  };
  const ct::PcaResult one = run(1);
  for (int threads : {2, 3, 5}) {
    const ct::PcaResult r = run(threads);
    ASSERT_EQ(r.components(), one.components());
    EXPECT_EQ(0, std::memcmp(r.basis.data(), one.basis.data(), sizeof(float) * one.basis.size()))
        << threads << " threads";
    EXPECT_EQ(0,
              std::memcmp(r.weights.data(), one.weights.data(), sizeof(float) * one.weights.size()))
        << threads << " threads";
  }
  omp_set_num_threads(omp_get_num_procs());
}
#endif
