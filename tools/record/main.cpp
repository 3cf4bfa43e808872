// candela-record: records a flame dataset from a V4L2 or libcamera camera. See README.md.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <optional>

#include "core/cli_usage.h"
#include "core/wxh.h"
#include "preview.h"
#include "recorder.h"

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  using namespace candela::record;
  RecordOptions o;
  CLI::App app{
      "candela-record: record a flame clip from a camera (V4L2 or libcamera) into a folder that\n"
      "`candela-tool ingest` reads (frames/*.png, info.txt, manifest.json).\n"
      "Exposure, gain and white balance are locked where the camera has them.\n"
      "Exit status: 0 done, 2 usage, 3 output folder not writable or full,\n"
      "4 no usable camera, 5 the camera went away (frames so far are kept).\n"
      "A live preview shows the frames being recorded when there is a display\n"
      "(--preview); closing its window or pressing Esc/q stops the recording like Ctrl-C.",
      "candela-record"};
  std::string size;
  app.add_option("--backend", o.backend,
                 "Camera backend: v4l2, libcamera, or auto (libcamera first, then V4L2; a /dev "
                 "path is always V4L2)")
      ->check(CLI::IsMember({"v4l2", "libcamera", "auto"}))
      ->capture_default_str();
  app.add_option("--device,-d", o.device,
                 "/dev/videoN (V4L2), a libcamera camera id (`cam -l`), or auto (the first)")
      ->capture_default_str();
  app.add_option("--out,-o", o.out, "Output folder (created; must not hold a recording)")
      ->required();
  app.add_option("--clip", o.clip, "Clip name in the manifest (default: the folder's name)");
  app.add_option("--size", size, "Frame size WxH (the camera's nearest is used)")
      ->default_str("640x480");
  app.add_option("--format", o.pixel_format,
                 "Pixel format: GREY, YUYV, UYVY, RGB3, BGR3 (default: camera's first usable)");
  app.add_option("--fps", o.fps, "Frame rate to ask for")
      ->check(CLI::Range(1, 240))
      ->capture_default_str();
  app.add_option("--frames,-n", o.frames, "Stop after N frames");
  app.add_option("--seconds", o.seconds, "Stop after S seconds")->check(CLI::NonNegativeNumber);
  app.add_flag("--color", o.color, "Write RGB PNGs (default: gray luma, like the flame footage)");
  app.add_flag("--keep-auto", o.keep_auto, "Leave auto exposure/gain/white balance alone");
  app.add_option("--exposure", o.exposure,
                 "Manual exposure (V4L2: the camera's units; libcamera: microseconds; default: "
                 "current)");
  app.add_option("--gain", o.gain, "Manual gain (libcamera: AnalogueGain; default: current)");
  app.add_option("--white-balance", o.white_balance,
                 "White balance temperature in K (default: current)");
  app.add_option("--queue", o.queue, "Frames buffered for the PNG writers")
      ->check(CLI::Range(2, 1024))
      ->capture_default_str();
  app.add_option("--writers", o.writers, "PNG writer threads")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  PreviewOptions po;
  std::string preview_size;
  app.add_option("--preview", po.mode,
                 "Live preview: auto (a window if $DISPLAY is set, else the DRM screen if one is\n"
                 "connected and free, else none), off, window, drm, headless")
      ->check(CLI::IsMember({"auto", "off", "window", "drm", "headless"}))
      ->capture_default_str();
  app.add_option("--preview-size", preview_size,
                 "Preview size WxH (default: the frame's size; DRM: the screen's mode)");
  app.add_option("--preview-device", po.drm_device,
                 "DRM card for the preview (default: the first with a free connected screen)");
  app.add_option("--preview-dump", po.dump_dir,
                 "Write the last preview image shown to DIR/preview.png at the end (tests)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a bad command line exits 2 as documented.
    return candela::usage_exit(app, e);
  }
  // --size and --preview-size: WxH, each side 16 to 8192.
  const auto parse_size = [](const std::string& text, const char* option, const char* example,
                             int& w, int& h) {
    const std::optional<candela::WxH> s = candela::parse_wxh(text, {16, 16}, {8192, 8192});
    if (!s) {
      std::fprintf(stderr, "candela-record: %s: expected WxH, e.g. %s, got '%s'\n", option, example,
                   text.c_str());
      return false;
    }
    w = s->width;
    h = s->height;
    return true;
  };
  if (!size.empty() && !parse_size(size, "--size", "640x480", o.width, o.height)) return kExitUsage;
  if (!preview_size.empty() &&
      !parse_size(preview_size, "--preview-size", "320x240", po.width, po.height))
    return kExitUsage;
  if (o.frames == 0 && o.seconds <= 0)
    std::fprintf(stderr, "candela-record: recording until Ctrl-C (no --frames or --seconds)\n");
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // Closing the preview (window, Esc, q) ends the recording the way Ctrl-C does.
  RecordPreview preview(po, [] { g_stop = true; });
  const RecordResult r = record(o, g_stop, &preview);
  preview.stop();
  if (r.written || r.seconds > 0)
    std::fprintf(stderr, "candela-record: %s\n", preview.summary().c_str());
  if (r.exit_code == kExitOk)
    std::fprintf(stderr,
                 "candela-record: %s: %llu frames in %.2f s (%.2f fps), %llu dropped -> %s\n",
                 r.message.c_str(), static_cast<unsigned long long>(r.written), r.seconds, r.fps,
                 static_cast<unsigned long long>(r.dropped), o.out.c_str());
  else if (r.written || r.seconds > 0)
    std::fprintf(stderr,
                 "candela-record: error: %s; %llu frames written so far are kept in %s "
                 "(manifest.json lists them)\n",
                 r.message.c_str(), static_cast<unsigned long long>(r.written), o.out.c_str());
  else
    std::fprintf(stderr, "candela-record: error: %s\n", r.message.c_str());
  return r.exit_code;
}
