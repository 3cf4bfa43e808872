#include "preview.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/image.h"
#include "core/log.h"
#include "display/display.h"
#include "gl/gles.h"
#include "gl/program.h"
#include "gl/texture.h"

namespace candela::record {
namespace {

// Backends explain themselves over several lines (one per card tried); the
// preview's log line and manifest entry keep it to one.
std::string one_line(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') {
      while (!out.empty() && out.back() == ' ') out.pop_back();
      if (!out.empty() && out.back() != ':') out += ';';
      out += ' ';
    } else if (c != ' ' || out.empty() || out.back() != ' ') {
      out += c;
    }
  }
  return out;
}

// The preview ignores the emulator's wind keys; only "quit" matters to it.
struct IgnoreKeys final : DisplayEvents {
  void on_key(Key) override {}
};

}  // namespace

PreviewChoice choose_preview(const std::string& mode, const char* display_env) {
  if (mode == "off") return {{}, "turned off (--preview off)"};
  if (mode == "window" || mode == "drm" || mode == "headless")
    return {{mode}, "asked for (--preview " + mode + ")"};
  if (mode != "auto")
    throw std::invalid_argument("--preview: expected auto, off, window, drm or headless, got '" +
                                mode + "'");
  if (display_env && *display_env)
    return {{"window", "drm"},
            std::string("auto: $DISPLAY is set (") + display_env +
                "): a window, else the DRM screen if one is connected and free"};
  return {{"drm"}, "auto: no $DISPLAY: the DRM screen if one is connected and free"};
}

PreviewRect letterbox(int fw, int fh, int dw, int dh) {
  if (fw <= 0 || fh <= 0 || dw <= 0 || dh <= 0) return {};
  PreviewRect r;
  // Integer arithmetic, so the tests can predict the rectangle exactly.
  if (static_cast<int64_t>(dw) * fh <= static_cast<int64_t>(dh) * fw) {
    r.width = dw;
    r.height = std::max<int>(1, static_cast<int>((static_cast<int64_t>(dw) * fh + fw / 2) / fw));
  } else {
    r.height = dh;
    r.width = std::max<int>(1, static_cast<int>((static_cast<int64_t>(dh) * fw + fh / 2) / fh));
  }
  r.x = (dw - r.width) / 2;
  r.y = (dh - r.height) / 2;
  return r;
}

PreviewRect recording_dot(int dw, int dh) {
  const int size = std::max(4, std::min(dw, dh) / 32);
  return {size / 2, size / 2, size, size};
}

RecordPreview::RecordPreview(PreviewOptions options, std::function<void()> on_quit)
    : options_(std::move(options)),
      choice_(choose_preview(options_.mode, std::getenv("DISPLAY"))),
      on_quit_(std::move(on_quit)) {}

RecordPreview::~RecordPreview() { stop(); }

void RecordPreview::start(int width, int height, int channels) {
  if (thread_.joinable() || state_ != State::kIdle) return;
  if (choice_.backends.empty()) {
    LOG_INFO("preview: %s", choice_.why.c_str());
    set_state(State::kOff, "", "");
    return;
  }
  LOG_INFO("preview: %s", choice_.why.c_str());
  width_ = width;
  height_ = height;
  channels_ = channels;
  frame_bytes_ = static_cast<size_t>(width) * height * channels;
  for (auto& b : buffers_) b.assign(frame_bytes_, 0);
  set_state(State::kOpening, "", "");
  accepting_ = true;
  thread_ = std::thread([this] { run(); });
}

void RecordPreview::push(const uint8_t* pixels, uint32_t sequence) {
  offered_.fetch_add(1, std::memory_order_relaxed);
  if (!accepting_.load(std::memory_order_acquire)) return;
  std::memcpy(buffers_[back_].data(), pixels, frame_bytes_);
  sequences_[back_] = sequence;
  back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & 3u;
  wake_.notify_one();  // no lock: a missed wake-up costs at most one wait period
}

bool RecordPreview::take_newest() {
  if (!(middle_.load(std::memory_order_acquire) & kFresh)) return false;
  front_ = middle_.exchange(front_, std::memory_order_acq_rel) & 3u;
  return true;
}

void RecordPreview::stop() {
  accepting_ = false;
  {
    std::lock_guard<std::mutex> lock(wake_mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void RecordPreview::set_state(State s, const std::string& backend, const std::string& error) {
  std::lock_guard<std::mutex> lock(status_mutex_);
  state_ = s;
  if (!backend.empty()) backend_ = backend;
  if (!error.empty() && error_.empty()) error_ = error;
  status_changed_.notify_all();
}

bool RecordPreview::wait_until_open() {
  std::unique_lock<std::mutex> lock(status_mutex_);
  status_changed_.wait(lock, [&] { return state_ != State::kOpening; });
  return state_ == State::kOpen;
}

std::string RecordPreview::backend() const {
  std::lock_guard<std::mutex> lock(status_mutex_);
  return backend_;
}

std::string RecordPreview::error() const {
  std::lock_guard<std::mutex> lock(status_mutex_);
  return error_;
}

std::string RecordPreview::manifest_json() const {
  std::lock_guard<std::mutex> lock(status_mutex_);
  nlohmann::ordered_json j;
  j["mode"] = options_.mode;
  j["backend"] = backend_;
  j["opened"] = !backend_.empty();
  j["shown"] = shown_.load();
  j["offered"] = offered_.load();
  j["last_sequence"] = last_shown_sequence_.load();
  if (!backend_.empty()) {
    j["width"] = display_width_;
    j["height"] = display_height_;
  }
  if (!error_.empty()) j["error"] = error_;
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string RecordPreview::summary() const {
  const std::string b = backend(), e = error();
  if (choice_.backends.empty()) return "no preview (--preview off)";
  if (b.empty()) return "no preview (" + (e.empty() ? std::string("not started") : e) + ")";
  std::string s = "preview on " + b + " showed " + std::to_string(shown_.load()) + " of " +
                  std::to_string(offered_.load()) + " frames";
  if (!e.empty()) s += " (then stopped: " + e + ")";
  return s;
}

void RecordPreview::run() {
  // The recording comes first: on a busy board the preview gets what is left.
  setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 10);
  std::unique_ptr<Display> display;
  std::string why_not;
  for (const auto& kind : choice_.backends) {
    DisplayOptions d;
    d.kind = kind;
    d.width = options_.width > 0 ? options_.width : (kind == "drm" ? 0 : width_);
    d.height = options_.height > 0 ? options_.height : (kind == "drm" ? 0 : height_);
    d.drm_device = options_.drm_device;
    try {
      display = open_display(d);
      break;
    } catch (const std::exception& e) {
      why_not += (why_not.empty() ? "" : "; ") + one_line(e.what());
    }
  }
  if (!display) {
    accepting_ = false;
    if (options_.mode == "auto")
      LOG_INFO("preview: no display free (%s): recording without a preview", why_not.c_str());
    else
      LOG_WARN("preview: cannot open %s (%s): recording without a preview", options_.mode.c_str(),
               why_not.c_str());
    set_state(State::kFailed, "", why_not);
    return;
  }

  std::vector<uint8_t> dump;  // the last image shown, bottom-up RGBA (glReadPixels order)
  int dump_w = 0, dump_h = 0;
  try {
    // GL objects are declared after `display`, so they go before its context does.
    Program program = Program::from_library("fullscreen.vert", "record_preview.frag");
    Texture texture = make_texture();
    VertexArray vao = make_vertex_array();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const bool gray = channels_ == 1;
    const GLenum format = gray ? GL_RED : GL_RGB;
    glTexImage2D(GL_TEXTURE_2D, 0, gray ? GL_R8 : GL_RGB8, width_, height_, 0, format,
                 GL_UNSIGNED_BYTE, nullptr);
    program.use();
    glUniform1i(program.uniform("u_frame"), 0);
    glUniform1i(program.uniform("u_gray"), gray ? 1 : 0);
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      display_width_ = display->width();
      display_height_ = display->height();
    }
    LOG_INFO("preview: showing the recording on %s (%dx%d)%s", std::string(display->name()).c_str(),
             display->width(), display->height(),
             display->name() == "window" ? "; close it or press Esc/q to stop recording" : "");
    set_state(State::kOpen, std::string(display->name()), "");

    IgnoreKeys keys;
    for (;;) {
      if (!display->poll_events(keys)) {
        LOG_INFO("preview: closed by the user: stopping the recording (as on Ctrl-C)");
        quit_ = true;
        accepting_ = false;
        if (on_quit_) on_quit_();
        break;
      }
      const bool stopping = stopping_.load();  // read before the take: the last frame is shown
      if (!take_newest()) {
        if (stopping) break;
        std::unique_lock<std::mutex> lock(wake_mutex_);
        wake_.wait_for(lock, std::chrono::milliseconds(20), [&] {
          return stopping_.load() || (middle_.load(std::memory_order_acquire) & kFresh);
        });
        continue;
      }
      const int dw = display->width(), dh = display->height();
      display->begin_frame();
      glBindTexture(GL_TEXTURE_2D, texture.get());
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, format, GL_UNSIGNED_BYTE,
                      buffers_[front_].data());
      glDisable(GL_DEPTH_TEST);
      glClearColor(0, 0, 0, 1);
      glClear(GL_COLOR_BUFFER_BIT);
      const PreviewRect r = letterbox(width_, height_, dw, dh);
      glViewport(r.x, dh - r.y - r.height, r.width, r.height);  // GL counts rows bottom up
      program.use();
      glBindVertexArray(vao.get());
      glDrawArrays(GL_TRIANGLES, 0, 3);
      // The recording indicator: a red square, cleared through a scissor (no extra program).
      const PreviewRect dot = recording_dot(dw, dh);
      glEnable(GL_SCISSOR_TEST);
      glScissor(dot.x, dh - dot.y - dot.height, dot.width, dot.height);
      glClearColor(0.9f, 0.05f, 0.05f, 1);
      glClear(GL_COLOR_BUFFER_BIT);
      glDisable(GL_SCISSOR_TEST);
      if (!options_.dump_dir.empty()) {
        // Read back before present(): after a swap the back buffer is undefined.
        if (dump_w != dw || dump_h != dh) dump.resize(static_cast<size_t>(dw) * dh * 4);
        dump_w = dw;
        dump_h = dh;
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, dw, dh, GL_RGBA, GL_UNSIGNED_BYTE, dump.data());
      }
      display->present();
      last_shown_sequence_ = sequences_[front_];
      shown_.fetch_add(1);
    }
    display->finish();
  } catch (const std::exception& e) {
    accepting_ = false;
    LOG_WARN("preview: stopped (%s): the recording goes on without it", one_line(e.what()).c_str());
    set_state(State::kFailed, "", one_line(e.what()));
  }
  if (!options_.dump_dir.empty() && dump_w > 0) {
    std::vector<uint8_t> rgb(static_cast<size_t>(dump_w) * dump_h * 3);
    for (int y = 0; y < dump_h; ++y)
      for (int x = 0; x < dump_w; ++x)
        for (int c = 0; c < 3; ++c)
          rgb[(static_cast<size_t>(y) * dump_w + x) * 3 + c] =
              dump[(static_cast<size_t>(dump_h - 1 - y) * dump_w + x) * 4 + c];
    const std::string path = options_.dump_dir + "/preview.png";
    try {
      std::error_code ec;
      std::filesystem::create_directories(options_.dump_dir, ec);
      write_png(path, dump_w, dump_h, 3, rgb.data());
      LOG_INFO("preview: wrote the last image shown (frame %lld) to %s",
               static_cast<long long>(last_shown_sequence_.load()), path.c_str());
    } catch (const std::exception& e) {
      LOG_WARN("preview: cannot write %s: %s", path.c_str(), e.what());
    }
  }
  display.reset();  // on this thread: the EGL context belongs to it
}

}  // namespace candela::record
