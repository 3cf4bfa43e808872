#include "ingest.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/image.h"

namespace candela::tools {
namespace fs = std::filesystem;

namespace {

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

const std::vector<float>& srgb_table() {
  static const std::vector<float> t = [] {
    std::vector<float> v(256);
    for (int i = 0; i < 256; ++i) v[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    return v;
  }();
  return t;
}

// Rec. 709 luma of linear RGB.
float linear_luma(uint8_t r, uint8_t g, uint8_t b) {
  const auto& t = srgb_table();
  return 0.2126f * t[r] + 0.7152f * t[g] + 0.0722f * t[b];
}

double fps_from_info(const fs::path& dir) {
  for (const fs::path& p : {dir / "info.txt", dir.parent_path() / "info.txt"}) {
    std::ifstream f(p);
    if (!f) continue;
    std::string text((std::istreambuf_iterator<char>(f)), {});
    // The first "<number> fps" in the text.
    for (size_t at = text.find(" fps"); at != std::string::npos; at = text.find(" fps", at + 1)) {
      size_t b = at;
      while (b > 0 && (std::isdigit(static_cast<unsigned char>(text[b - 1])) || text[b - 1] == '.'))
        --b;
      if (b < at) return std::stod(text.substr(b, at - b));
    }
  }
  return 0;
}

SourceClip read_png_folder(const fs::path& dir0, int max_frames, int step) {
  fs::path dir = dir0;
  if (fs::is_directory(dir / "frames")) dir = dir / "frames";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".png" &&
        e.path().filename().string().find("contact") == std::string::npos)
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw ConfigError(dir0.string(), "", "no PNG frames found");
  SourceClip c;
  c.name = fs::path(dir0).filename().string();
  if (c.name.empty() || c.name == "frames")
    c.name = fs::path(dir0).parent_path().filename().string();
  c.source = dir0.string();
  double fps = fps_from_info(dir);
  c.fps = fps > 0 ? fps : 30;
  for (size_t i = 0; i < files.size(); i += step) {
    if (max_frames > 0 && c.frames() >= max_frames) break;
    Image img = read_png(files[i].string(), 0);
    if (c.width == 0) {
      c.width = img.width;
      c.height = img.height;
    } else if (img.width != c.width || img.height != c.height) {
      throw ConfigError(files[i].string(), "", "frame size differs from the first frame's");
    }
    const size_t px = static_cast<size_t>(img.width) * img.height;
    const size_t at = c.luma.size();
    c.luma.resize(at + px);
    for (size_t p = 0; p < px; ++p) {
      const uint8_t* s = img.pixels.data() + p * img.channels;
      c.luma[at + p] = img.channels >= 3 ? linear_luma(s[0], s[1], s[2]) : srgb_table()[s[0]];
    }
  }
  return c;
}

std::string av_err(int e) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(e, buf, sizeof buf);
  return buf;
}

SourceClip read_video(const std::string& path, int max_frames, int step) {
  AVFormatContext* fmt = nullptr;
  int rc = avformat_open_input(&fmt, path.c_str(), nullptr, nullptr);
  if (rc < 0) throw ConfigError(path, "", "cannot open video: " + av_err(rc));
  struct Cleanup {
    AVFormatContext** fmt;
    AVCodecContext* dec = nullptr;
    AVPacket* pkt = nullptr;
    AVFrame* frame = nullptr;
    SwsContext* sws = nullptr;
    ~Cleanup() {
      sws_freeContext(sws);
      av_frame_free(&frame);
      av_packet_free(&pkt);
      avcodec_free_context(&dec);
      avformat_close_input(fmt);
    }
  } cl{&fmt};
  if ((rc = avformat_find_stream_info(fmt, nullptr)) < 0)
    throw ConfigError(path, "", "no stream information: " + av_err(rc));
  const AVCodec* codec = nullptr;
  const int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (si < 0 || !codec) throw ConfigError(path, "", "no decodable video stream");
  AVStream* st = fmt->streams[si];
  cl.dec = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(cl.dec, st->codecpar);
  if ((rc = avcodec_open2(cl.dec, codec, nullptr)) < 0)
    throw ConfigError(path, "", "cannot open decoder: " + av_err(rc));
  SourceClip c;
  c.name = fs::path(path).stem().string();
  c.source = path;
  AVRational r = st->avg_frame_rate.num ? st->avg_frame_rate : st->r_frame_rate;
  c.fps = r.num && r.den ? av_q2d(r) : 30;
  cl.pkt = av_packet_alloc();
  cl.frame = av_frame_alloc();
  std::vector<uint8_t> rgb;
  int index = 0;
  bool done = false;
  auto take = [&]() {
    while (!done && avcodec_receive_frame(cl.dec, cl.frame) == 0) {
      if (index++ % step != 0) continue;
      const int w = cl.frame->width, h = cl.frame->height;
      if (c.width == 0) {
        c.width = w;
        c.height = h;
      } else if (w != c.width || h != c.height) {
        throw ConfigError(path, "", "frame size changes within the video");
      }
      cl.sws = sws_getCachedContext(cl.sws, w, h, static_cast<AVPixelFormat>(cl.frame->format), w,
                                    h, AV_PIX_FMT_RGB24, SWS_BILINEAR, nullptr, nullptr, nullptr);
      if (!cl.sws) throw ConfigError(path, "", "cannot convert the pixel format");
      rgb.resize(static_cast<size_t>(w) * h * 3);
      uint8_t* dst[1] = {rgb.data()};
      int dst_stride[1] = {3 * w};
      sws_scale(cl.sws, cl.frame->data, cl.frame->linesize, 0, h, dst, dst_stride);
      const size_t at = c.luma.size();
      c.luma.resize(at + static_cast<size_t>(w) * h);
      for (size_t p = 0; p < static_cast<size_t>(w) * h; ++p)
        c.luma[at + p] = linear_luma(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
      if (max_frames > 0 && c.frames() >= max_frames) done = true;
    }
  };
  while (!done && av_read_frame(fmt, cl.pkt) >= 0) {
    if (cl.pkt->stream_index == si) {
      avcodec_send_packet(cl.dec, cl.pkt);
      take();
    }
    av_packet_unref(cl.pkt);
  }
  if (!done) {
    avcodec_send_packet(cl.dec, nullptr);  // flush
    take();
  }
  if (c.frames() == 0) throw ConfigError(path, "", "no frames could be decoded");
  return c;
}

}  // namespace

SourceClip read_source(const std::string& input, int max_frames, int step, double fps_override) {
  if (step < 1) step = 1;
  std::error_code ec;
  if (!fs::exists(input, ec)) throw ConfigError(input, "", "no such file or folder");
  // A FIFO or device would be read (or waited on) for ever: footage is a
  // folder of frames or a video file (issue 34: ingest FIFO hung).
  const fs::file_status st = fs::status(input, ec);
  if (!fs::is_directory(st) && !fs::is_regular_file(st))
    throw ConfigError(input, "", "expected a folder of PNG frames or a video file");
  SourceClip c = fs::is_directory(st) ? read_png_folder(input, max_frames, step)
                                      : read_video(input, max_frames, step);
  if (fps_override > 0) c.fps = fps_override;
  c.fps /= step;
  return c;
}

IngestOptions::Label parse_label(const std::string& text, const std::string& what) {
  // CLIP:FROM-TO:LABEL; the clip name may itself hold colons, so split from the right.
  auto bad = [&]() -> ConfigError {
    return ConfigError(what, text, "expected CLIP:FROM-TO:LABEL, e.g. breeze:55-100:wind-right");
  };
  const size_t c2 = text.rfind(':');
  const size_t c1 =
      c2 == std::string::npos || c2 == 0 ? std::string::npos : text.rfind(':', c2 - 1);
  if (c1 == std::string::npos || c1 == 0) throw bad();
  IngestOptions::Label l;
  l.clip = text.substr(0, c1);
  l.label = text.substr(c2 + 1);
  const std::string range = text.substr(c1 + 1, c2 - c1 - 1);
  const size_t dash = range.find('-');
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 9 || !std::all_of(s.begin(), s.end(), [](char ch) {
          return std::isdigit(static_cast<unsigned char>(ch));
        }))
      throw bad();
    return std::stoi(s);
  };
  if (dash == std::string::npos || l.label.empty()) throw bad();
  for (char ch : l.label)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_' && ch != '.')
      throw bad();
  l.from = number(range.substr(0, dash));
  l.to = number(range.substr(dash + 1));
  if (l.to <= l.from) throw ConfigError(what, text, "expected FROM < TO");
  return l;
}

int count_plumes(const uint8_t* frame, int width, int height, float level, float min_area) {
  const size_t n = static_cast<size_t>(width) * height;
  const uint8_t peak = *std::max_element(frame, frame + n);
  if (peak == 0) return 0;
  const float cut = std::max(1.0f, level * peak);
  std::vector<int> label(n, 0);
  std::vector<int> areas;
  std::vector<size_t> stack;
  size_t total = 0;
  for (size_t s = 0; s < n; ++s) {
    if (frame[s] < cut || label[s]) continue;
    const int id = static_cast<int>(areas.size()) + 1;
    int area = 0;
    stack.push_back(s);
    label[s] = id;
    while (!stack.empty()) {
      const size_t p = stack.back();
      stack.pop_back();
      ++area;
      const int x = static_cast<int>(p % width), y = static_cast<int>(p / width);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t q = static_cast<size_t>(ny) * width + nx;
          if (frame[q] >= cut && !label[q]) {
            label[q] = id;
            stack.push_back(q);
          }
        }
    }
    areas.push_back(area);
    total += area;
  }
  int plumes = 0;
  for (int a : areas)
    if (a >= std::max(4.0f, min_area * static_cast<float>(total))) ++plumes;
  return plumes;
}

Dataset ingest(const std::vector<SourceClip>& clips, const IngestOptions& opt,
               const Progress& progress) {
  if (clips.empty()) throw ConfigError("ingest", "INPUT", "at least one input");
  Dataset d;
  d.width = opt.width;
  d.height = opt.height;
  const size_t opx = d.frame_pixels();
  int total = 0;
  for (const auto& c : clips) total += c.frames();
  d.pixels.assign(opx * total, 0);
  d.multi_plume.assign(total, 0);
  std::vector<float> dark;
  int next = 0;
  for (const auto& c : clips) {
    const int w = c.width, h = c.height, nf = c.frames();
    const size_t px = static_cast<size_t>(w) * h;
    // Background: a dark reference frame (resized by nearest neighbour) and/or a level.
    dark.assign(px, 0.0f);
    if (!opt.dark_frame.empty()) {
      Image img = read_png(opt.dark_frame, 1);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          dark[static_cast<size_t>(y) * w + x] =
              srgb_table()[img.at(x * img.width / w, y * img.height / h)];
    }
    float level = opt.threshold;
    if (level < 0 && opt.as_filmed) level = 0;
    if (level < 0) {
      // Most of a flame clip is background: twice its median (plus a floor) is above it.
      std::vector<float> sample;
      for (size_t i = 0; i < c.luma.size(); i += 97) sample.push_back(c.luma[i] - dark[i % px]);
      std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
      level = std::clamp(2.0f * sample[sample.size() / 2] + 0.01f, 0.01f, 0.5f);
    }
    // Mean background-free image: finds the base, centre and height of the flame.
    std::vector<double> mean(px, 0.0);
    for (int f = 0; f < nf; ++f)
      for (size_t p = 0; p < px; ++p)
        mean[p] += std::max(0.0f, c.luma[f * px + p] - dark[p] - level);
    std::vector<double> rows(h, 0.0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) rows[y] += mean[static_cast<size_t>(y) * w + x];
    const double peak = *std::max_element(rows.begin(), rows.end());
    if (!(peak > 0))
      throw ConfigError(c.source, "", "no flame found (everything is below the background level)");
    int base = h - 1, top = 0;
    while (base > 0 && rows[base] < 0.1 * peak) --base;
    while (top < base && rows[top] < 0.02 * peak) ++top;
    double cx_num = 0, cx_den = 0;
    const int band = std::max(1, (base - top) / 4);
    for (int y = std::max(0, base - band); y <= base; ++y)
      for (int x = 0; x < w; ++x) {
        cx_num += x * mean[static_cast<size_t>(y) * w + x];
        cx_den += mean[static_cast<size_t>(y) * w + x];
      }
    const double cx = cx_den > 0 ? cx_num / cx_den : w / 2.0;
    // Output pixels per input pixel: the flame's extent spans top_row..base_row.
    double scale = (opt.base_row - opt.top_row) * d.height / std::max(1, base - top + 1);
    double ox = cx - (d.width / 2.0) / scale;            // input x of output x = 0
    double oy = base - opt.base_row * d.height / scale;  // input y of output y = 0
    if (opt.as_filmed) {                                 // the whole frame, centred
      scale = std::min(static_cast<double>(d.width) / w, static_cast<double>(d.height) / h);
      ox = (w - d.width / scale) / 2;
      oy = (h - d.height / scale) / 2;
    }
    const int ss = std::clamp(static_cast<int>(std::ceil(1.0 / scale)), 1, 4);  // supersampling
    if (progress)
      progress(c.name + ": " + std::to_string(nf) + " frames " + std::to_string(w) + "x" +
               std::to_string(h) + ", background " + std::to_string(level) + ", base row " +
               std::to_string(base) + ", centre x " + std::to_string(static_cast<int>(cx)));
    auto sample = [&](const float* img, double x, double y) -> float {
      // Bilinear; outside the frame is background.
      x -= 0.5;
      y -= 0.5;
      const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
      const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
      float acc = 0;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const int xi = x0 + i, yj = y0 + j;
          if (xi < 0 || yj < 0 || xi >= w || yj >= h) continue;
          const size_t p = static_cast<size_t>(yj) * w + xi;
          const float v = std::max(0.0f, img[p] - dark[p] - level) / (1.0f - level);
          acc += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * v;
        }
      return acc;
    };
    for (int f = 0; f < nf; ++f) {
      const float* img = c.luma.data() + f * px;
      uint8_t* out = d.pixels.data() + opx * (next + f);
      for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
          float acc = 0;
          for (int sy = 0; sy < ss; ++sy)
            for (int sx = 0; sx < ss; ++sx)
              acc += sample(img, ox + (x + (sx + 0.5) / ss) / scale,
                            oy + (y + (sy + 0.5) / ss) / scale);
          acc /= static_cast<float>(ss * ss);
          // Background removal and resampling are done in linear light; the
          // dataset stores display-encoded values, as the footage had them: the
          // eigen-images then learn what a viewer sees (the eval scripts
          // measure that too), the runtime shows gray as lightness without a
          // further curve, and 8 bits keep the flame's dim edges.
          out[static_cast<size_t>(y) * d.width + x] = encode_srgb8(acc);
        }
      d.multi_plume[next + f] =
          count_plumes(out, d.width, d.height, opt.plume_level, opt.plume_min_area) >= 2;
    }
    model::ClipInfo ci;
    ci.name = c.name;
    ci.source = c.source;
    ci.first = next;
    ci.count = nf;
    ci.fps = c.fps;
    for (const auto& l : opt.labels) {
      if (l.clip != c.name) continue;
      if (l.to > nf)
        throw ConfigError("--label", l.clip,
                          "range ends after the clip's " + std::to_string(nf) + " frames");
      ci.labels.push_back({next + l.from, next + l.to, l.label});
    }
    d.clips.push_back(std::move(ci));
    next += nf;
  }
  for (const auto& l : opt.labels) {
    bool found = false;
    for (const auto& c : d.clips) found |= c.name == l.clip;
    if (!found) throw ConfigError("--label", l.clip, "no input clip has this name");
  }
  d.options = {{"width", opt.width},
               {"height", opt.height},
               {"threshold", opt.threshold},
               {"as_filmed", opt.as_filmed},
               {"dark_frame", opt.dark_frame},
               {"base_row", opt.base_row},
               {"top_row", opt.top_row},
               {"plume_level", opt.plume_level},
               {"plume_min_area", opt.plume_min_area}};
  return d;
}

}  // namespace candela::tools
