// libcamera backend of VideoCapture. Completed requests arrive on libcamera's
// own thread; they are queued here and announced through an eventfd, so
// next() sleeps in poll() on that and the caller's wake fd, like V4L2.
#include "input/libcamera_capture.h"

#include <dirent.h>
#include <fcntl.h>
#include <libcamera/libcamera.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/json.h"
#include "core/log.h"
#include "input/v4l2_capture.h"

namespace candela {
namespace {

namespace lc = libcamera;

// libcamera's INFO/WARN lines (e.g. vimc's "no static properties") would fill
// the kiosk's log on every retry. It creates its log categories lazily and
// reads their levels from this variable, so it is the only switch that reaches
// them all; a user's own setting wins (no overwrite). Set during static
// initialisation, before any thread exists: setenv() racing another thread's
// getenv() is undefined.
[[maybe_unused]] const bool kLibcameraLogQuiet = setenv("LIBCAMERA_LOG_LEVELS", "*:ERROR", 0) == 0;

// --- Camera device nodes that libcamera opened -----------------------------------
// When a camera's driver goes (unplugged, unbound) without libcamera being
// told (libcamera 0.0.3 misses it: no disconnected signal), its thread keeps
// polling the dead nodes, which answer POLLERR at once, for ever: it spins a
// whole core. On a one-core board that starves every other thread (the
// recorder's preview never finished and the recorder exited minutes late).
// The nodes libcamera opened are noted here (the device nodes that appear in
// /proc/self/fd while it enumerates and starts a camera), so that once one is
// found deleted it can be silenced: the same fd number then refers to the
// read end of a pipe nobody writes, which never polls ready. The number stays
// taken (libcamera still owns it and will close it), so nothing else can be
// given it meanwhile.
struct NodeFd {
  int fd;
  dev_t dev;
  ino_t ino;
  bool operator==(const NodeFd& o) const { return fd == o.fd && dev == o.dev && ino == o.ino; }
};

bool is_camera_node_path(const char* target) {
  return std::strncmp(target, "/dev/video", 10) == 0 ||
         std::strncmp(target, "/dev/media", 10) == 0 ||
         std::strncmp(target, "/dev/v4l-subdev", 15) == 0;
}

// The open fds of this process that are video, media or sub-device nodes;
// *deleted: those the kernel has removed from /dev ("/dev/video6 (deleted)").
std::vector<NodeFd> open_camera_nodes(std::vector<NodeFd>* deleted = nullptr) {
  std::vector<NodeFd> out;
  DIR* d = opendir("/proc/self/fd");
  if (!d) return out;
  while (dirent* e = readdir(d)) {
    char target[256];
    const std::string link = std::string("/proc/self/fd/") + e->d_name;
    const ssize_t n = readlink(link.c_str(), target, sizeof target - 1);
    if (n <= 0) continue;
    target[n] = 0;
    if (!is_camera_node_path(target)) continue;
    const int fd = std::atoi(e->d_name);
    struct stat st {};
    if (fd == dirfd(d) || fstat(fd, &st) != 0) continue;
    out.push_back({fd, st.st_dev, st.st_ino});
    if (deleted && std::strstr(target, " (deleted)")) deleted->push_back(out.back());
  }
  closedir(d);
  return out;
}

class LibcameraNodes {
 public:
  static LibcameraNodes& get() {
    static auto* nodes = new LibcameraNodes;  // never destroyed: used until exit
    return *nodes;
  }
  // Call with the device nodes open before libcamera opened anything.
  void note_opened_since(const std::vector<NodeFd>& before) {
    const auto now = open_camera_nodes();
    std::lock_guard<std::mutex> lock(mutex_);
    for (const NodeFd& n : now)
      if (std::find(before.begin(), before.end(), n) == before.end() &&
          std::find(owned_.begin(), owned_.end(), n) == owned_.end())
        owned_.push_back(n);
  }
  // Silences every node of libcamera's that the kernel removed; how many it
  // silenced now.
  int silence_removed() {
    std::vector<NodeFd> deleted;
    open_camera_nodes(&deleted);
    std::lock_guard<std::mutex> lock(mutex_);
    int removed = 0;
    for (const NodeFd& n : deleted) {
      if (std::find(owned_.begin(), owned_.end(), n) == owned_.end()) continue;
      if (quiet_read_ < 0) {
        int p[2];
        if (pipe2(p, O_CLOEXEC) != 0) return removed;
        quiet_read_ = p[0];
        quiet_write_ = p[1];  // kept open: a pipe without writers polls POLLHUP
      }
      if (dup3(quiet_read_, n.fd, O_CLOEXEC) < 0) continue;
      ++silenced_;
      ++removed;
      owned_.erase(std::find(owned_.begin(), owned_.end(), n));
    }
    return removed;
  }
  bool any_silenced() {
    std::lock_guard<std::mutex> lock(mutex_);
    return silenced_ > 0;
  }

 private:
  std::mutex mutex_;
  std::vector<NodeFd> owned_;
  size_t silenced_ = 0;
  int quiet_read_ = -1, quiet_write_ = -1;
};

// libcamera allows one CameraManager per process: the captures share it, and
// it goes when the last of them does (the next open enumerates afresh).
std::shared_ptr<lc::CameraManager> shared_manager() {
  static std::mutex mutex;
  static std::weak_ptr<lc::CameraManager> weak;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto cm = weak.lock()) return cm;
  const auto before = open_camera_nodes();
  std::shared_ptr<lc::CameraManager> cm(new lc::CameraManager, [](lc::CameraManager* m) {
    m->stop();
    delete m;
  });
  if (const int r = cm->start(); r < 0)
    throw RuntimeError(std::string("libcamera: cannot start the camera manager: ") +
                       std::strerror(-r));
  LibcameraNodes::get().note_opened_since(before);
  weak = cm;
  return cm;
}

// Cameras lost without libcamera being told (see close_all): kept, started
// and acquired, for the life of the process. The manager they belong to
// still lists them, so a retry would find one "busy" (held by this very
// process): open() asks here first and says what really happened.
struct Abandoned {
  std::vector<std::unique_ptr<lc::Request>> requests;
  std::unique_ptr<lc::FrameBufferAllocator> allocator;
  std::unique_ptr<lc::CameraConfiguration> config;
  std::shared_ptr<lc::Camera> camera;
  std::shared_ptr<lc::CameraManager> manager;
};
std::mutex abandoned_mutex;
std::vector<Abandoned>& abandoned_cameras() {
  static auto* list = new std::vector<Abandoned>;  // reachable, never destroyed
  return *list;
}
bool is_abandoned(const lc::Camera* camera) {
  std::lock_guard<std::mutex> lock(abandoned_mutex);
  for (const Abandoned& a : abandoned_cameras())
    if (a.camera.get() == camera) return true;
  return false;
}
// Takes a lost camera off its manager's list, so that retries see it gone
// (not "busy": held by this process) and the camera, when it comes back, can
// be registered again: libcamera 0.0.3 aborts the whole process ("Trying to
// register a camera with a duplicated ID") when a camera it was not told
// about comes back under the same id. CameraManager::removeCamera() must run
// on the manager's own thread (it asserts so), the thread the camera was
// made on: a blocking call there through an object moved to it.
// (Public in libcamera 0.0.3, private in later releases, which are told of
// a lost camera themselves: checked at compile time.)
class ManagerThreadCall : public lc::Object {
 public:
  explicit ManagerThreadCall(std::function<void()> fn) : fn_(std::move(fn)) {}
  void run() { fn_(); }

 private:
  std::function<void()> fn_;
};
template <typename Manager>
void forget_camera(Manager* manager, const std::shared_ptr<lc::Camera>& camera) {
  if constexpr (requires(Manager * m, std::shared_ptr<lc::Camera> c) { m->removeCamera(c); }) {
    if (!manager || !camera || !camera->thread()) return;
    auto* call = new ManagerThreadCall([manager, camera] { manager->removeCamera(camera); });
    call->moveToThread(camera->thread());
    call->invokeMethod(&ManagerThreadCall::run, lc::ConnectionTypeBlocking);
    call->deleteLater();  // on that thread
  }
}

std::string lost_camera_error(const std::string& id) {
  return "libcamera: camera \"" + id +
         "\" was lost (unplugged or its driver unbound) without libcamera being told, and "
         "libcamera still lists it: it cannot be opened again until candela restarts "
         "(libcamera allows one camera manager per process)";
}

// Scalars as JSON numbers/booleans; arrays and the rest as JSON strings.
std::string control_json(const lc::ControlValue& v) {
  nlohmann::json j;  // null
  if (v.isNone()) return j.dump();
  if (v.isArray()) {
    j = v.toString();
  } else {
    switch (v.type()) {
      case lc::ControlTypeBool:
        j = v.get<bool>();
        break;
      case lc::ControlTypeByte:
        j = v.get<uint8_t>();
        break;
      case lc::ControlTypeInteger32:
        j = v.get<int32_t>();
        break;
      case lc::ControlTypeInteger64:
        j = v.get<int64_t>();
        break;
      case lc::ControlTypeFloat:  // six significant digits (%g); NaN and infinities: null
        j = json_digits(static_cast<double>(v.get<float>()), 6);
        break;
      default:
        j = v.toString();
        break;
    }
  }
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

class LibcameraCapture final : public VideoCapture {
 public:
  explicit LibcameraCapture(const CaptureSettings& s);
  ~LibcameraCapture() override { close_all(); }
  LibcameraCapture(const LibcameraCapture&) = delete;
  LibcameraCapture& operator=(const LibcameraCapture&) = delete;

  Result next(VideoFrame& frame, int timeout_ms, int wake_fd) override;
  void release(const VideoFrame& frame) override;
  const VideoFormat& format() const override { return format_; }
  const std::string& error() const override { return error_; }
  const char* backend() const override { return "libcamera"; }
  const std::string& device() const override { return id_; }
  const std::string& card() const override { return model_; }
  const std::string& driver() const override { return driver_; }
  std::vector<CaptureControl> controls() override;
  std::vector<LockedControl> lock_auto(const AutoLockRequest& request) override;

 private:
  void on_completed(lc::Request* request);
  void on_disconnected();
  void close_all();
  void notify();

  std::string id_, model_, driver_ = "libcamera", error_;
  VideoFormat format_;
  std::shared_ptr<lc::CameraManager> manager_;
  std::shared_ptr<lc::Camera> camera_;
  std::unique_ptr<lc::CameraConfiguration> config_;
  std::unique_ptr<lc::FrameBufferAllocator> allocator_;
  lc::Stream* stream_ = nullptr;
  std::vector<std::unique_ptr<lc::Request>> requests_;
  struct Mapping {
    void* base = nullptr;
    size_t length = 0;
    const uint8_t* data = nullptr;  // the first plane
    size_t plane_length = 0;
  };
  std::vector<Mapping> mappings_;  // by request cookie
  bool acquired_ = false, started_ = false, connected_ = false;
  int event_fd_ = -1;

  // Filled on libcamera's thread, emptied by next(): a ring of completed
  // requests (never more than there are requests, so no allocation per frame).
  std::mutex mutex_;
  std::vector<lc::Request*> done_;
  size_t done_head_ = 0, done_count_ = 0;
  std::atomic<bool> gone_{false};  // lost: unplugged, or a request could not be queued
  std::atomic<bool> disconnected_{false};
  bool stalled_ = false;  // the last next() timed out  // libcamera says so (Camera::disconnected)
  lc::ControlList pending_controls_;  // applied to the next request queued
  lc::ControlList last_metadata_;     // of the first frame handed out
  bool metadata_seen_ = false;
  bool nodes_removed_ = false;        // its device nodes went from /dev (silenced)
  std::vector<NodeFd> nodes_before_;  // camera nodes open before this camera's
};

LibcameraCapture::LibcameraCapture(const CaptureSettings& s) {
  try {
    manager_ = shared_manager();
    const auto cameras = manager_->cameras();
    if (s.device == "auto" || s.device.empty()) {
      if (cameras.empty())
        throw RuntimeError(
            "libcamera: no camera found (libcamera lists none: is the camera connected and, "
            "for USB or vimc cameras, udev running?)");
      // The first one this process has not lost.
      for (const auto& c : cameras)
        if (!is_abandoned(c.get())) {
          camera_ = c;
          break;
        }
      if (!camera_) throw RuntimeError(lost_camera_error(cameras.front()->id()));
    } else {
      camera_ = manager_->get(s.device);
      if (!camera_) {
        std::string known;
        for (const auto& c : cameras)
          known += (known.empty() ? "" : ", ") + ("\"" + c->id() + "\"");
        throw RuntimeError("libcamera: no camera \"" + s.device +
                           "\" (cameras: " + (known.empty() ? "none" : known) + ")");
      }
    }
    if (is_abandoned(camera_.get())) throw RuntimeError(lost_camera_error(camera_->id()));
    id_ = camera_->id();
    model_ = camera_->properties().get(lc::properties::Model).value_or(id_);
    nodes_before_ = open_camera_nodes();
    if (const int r = camera_->acquire(); r < 0)
      throw RuntimeError("libcamera: camera \"" + id_ + "\": " +
                         (r == -EBUSY ? std::string("busy (in use by another program)")
                                      : std::string("cannot acquire: ") + std::strerror(-r)));
    acquired_ = true;

    config_ = camera_->generateConfiguration({lc::StreamRole::Viewfinder});
    if (!config_ || config_->empty())
      throw RuntimeError("libcamera: camera \"" + id_ + "\" has no viewfinder stream");
    lc::StreamConfiguration& sc = config_->at(0);
    // Cheap-to-gray formats first, unless one is asked for.
    const auto offered = sc.formats().pixelformats();
    uint32_t want = s.fourcc ? libcamera_fourcc_from_v4l2(s.fourcc) : 0;
    if (s.fourcc && !want)
      throw RuntimeError("libcamera: format " + fourcc_name(s.fourcc) +
                         " has no libcamera equivalent candela reads");
    if (!want) {
      for (uint32_t v4l2 :
           {V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_UYVY, V4L2_PIX_FMT_NV12,
            V4L2_PIX_FMT_YUV420, V4L2_PIX_FMT_RGB24, V4L2_PIX_FMT_BGR24}) {
        const uint32_t drm = libcamera_fourcc_from_v4l2(v4l2);
        for (const lc::PixelFormat& pf : offered)
          if (pf.fourcc() == drm && pf.modifier() == 0) want = drm;
        if (want) break;
      }
    }
    if (!want) {
      std::string names;
      for (const lc::PixelFormat& pf : offered) names += " " + pf.toString();
      throw RuntimeError("libcamera: camera \"" + id_ +
                         "\" offers no format candela reads (it offers:" + names + ")");
    }
    sc.pixelFormat = lc::PixelFormat(want);
    sc.size = lc::Size(static_cast<unsigned>(s.width), static_cast<unsigned>(s.height));
    sc.bufferCount = static_cast<unsigned>(std::max(2, s.buffers));
    const auto status = config_->validate();
    if (status == lc::CameraConfiguration::Invalid)
      throw RuntimeError("libcamera: camera \"" + id_ + "\" rejects " + sc.toString());
    format_.fourcc = v4l2_fourcc_from_libcamera(sc.pixelFormat.fourcc());
    if (!format_.fourcc || sc.pixelFormat.modifier() != 0)
      throw RuntimeError("libcamera: camera \"" + id_ + "\" adjusted the format to " +
                         sc.pixelFormat.toString() + ", which candela does not read");
    if (status == lc::CameraConfiguration::Adjusted)
      LOG_INFO("libcamera: camera \"%s\": asked for %dx%d, got %s", id_.c_str(), s.width, s.height,
               sc.toString().c_str());
    if (const int r = camera_->configure(config_.get()); r < 0)
      throw RuntimeError("libcamera: camera \"" + id_ + "\": cannot configure " + sc.toString() +
                         ": " + std::strerror(-r));
    stream_ = sc.stream();
    format_.width = static_cast<int>(sc.size.width);
    format_.height = static_cast<int>(sc.size.height);
    const int bpp = format_.fourcc == V4L2_PIX_FMT_YUYV || format_.fourcc == V4L2_PIX_FMT_UYVY ? 2
                    : format_.fourcc == V4L2_PIX_FMT_RGB24 || format_.fourcc == V4L2_PIX_FMT_BGR24
                        ? 3
                        : 1;
    format_.bytesperline = std::max(static_cast<int>(sc.stride), format_.width * bpp);
    format_.sizeimage = sc.frameSize;

    allocator_ = std::make_unique<lc::FrameBufferAllocator>(camera_);
    if (allocator_->allocate(stream_) < 0)
      throw RuntimeError("libcamera: camera \"" + id_ + "\": cannot allocate buffers");
    const auto& buffers = allocator_->buffers(stream_);
    if (buffers.size() < 2)
      throw RuntimeError("libcamera: camera \"" + id_ + "\": fewer than 2 buffers");
    event_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    if (event_fd_ < 0) throw RuntimeError("libcamera: cannot create an eventfd");
    for (size_t i = 0; i < buffers.size(); ++i) {
      lc::FrameBuffer* fb = buffers[i].get();
      const lc::FrameBuffer::Plane& plane = fb->planes().front();
      // Map from the start of the dmabuf: a plane's offset need not be page aligned.
      Mapping m;
      m.length = plane.offset + plane.length;
      m.base = mmap(nullptr, m.length, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
      if (m.base == MAP_FAILED)
        throw RuntimeError("libcamera: camera \"" + id_ + "\": mmap: " + std::strerror(errno));
      m.data = static_cast<const uint8_t*>(m.base) + plane.offset;
      m.plane_length = plane.length;
      mappings_.push_back(m);
      auto request = camera_->createRequest(i);
      if (!request || request->addBuffer(stream_, fb) < 0)
        throw RuntimeError("libcamera: camera \"" + id_ + "\": cannot create a request");
      requests_.push_back(std::move(request));
    }
    done_.resize(requests_.size());

    camera_->requestCompleted.connect(this, &LibcameraCapture::on_completed);
    camera_->disconnected.connect(this, &LibcameraCapture::on_disconnected);
    connected_ = true;

    lc::ControlList start_controls(camera_->controls());
    const lc::ControlInfoMap& offered_controls = camera_->controls();
    if (s.fps > 0 && offered_controls.count(&lc::controls::FrameDurationLimits)) {
      const int64_t us = 1'000'000 / s.fps;
      start_controls.set(lc::controls::FrameDurationLimits, lc::Span<const int64_t, 2>({us, us}));
      format_.fps = s.fps;
    } else if (s.fps > 0) {
      LOG_INFO(
          "libcamera: camera \"%s\" offers no FrameDurationLimits: it runs at its own rate, "
          "not %d fps",
          id_.c_str(), s.fps);
    }
    if (const int r = camera_->start(&start_controls); r < 0)
      throw RuntimeError("libcamera: camera \"" + id_ + "\": cannot start: " + std::strerror(-r));
    started_ = true;
    LibcameraNodes::get().note_opened_since(nodes_before_);
    for (auto& r : requests_)
      if (camera_->queueRequest(r.get()) < 0)
        throw RuntimeError("libcamera: camera \"" + id_ + "\": cannot queue a request");
  } catch (...) {
    close_all();
    throw;
  }
}

// Whether this process holds a camera device node that is gone from /dev:
// the kernel unregistered it (unplugged, driver unbound) while the fd stayed
// open, and the fd's link then reads "/dev/video6 (deleted)".
bool holds_deleted_camera_node() {
  std::vector<NodeFd> deleted;
  open_camera_nodes(&deleted);
  return !deleted.empty();
}

void LibcameraCapture::close_all() {
  if (camera_ && started_ && !disconnected_ && (gone_ || stalled_) &&
      (nodes_removed_ || LibcameraNodes::get().any_silenced() || holds_deleted_camera_node())) {
    // The camera went away but libcamera has not noticed (no udev event
    // reached it). Stopping it now trips an assertion in libcamera 0.0.3
    // (requests still queued in a pipeline whose STREAMOFF failed) that
    // aborts the process: leave its objects be instead; the frames recorded
    // so far matter more than a few leaked handles.
    LOG_WARN(
        "libcamera: camera \"%s\" is gone but libcamera was not told; leaving it unstopped and "
        "taking it off libcamera's list (it is opened afresh when it comes back)",
        id_.c_str());
    if (connected_) {
      camera_->requestCompleted.disconnect(this, &LibcameraCapture::on_completed);
      camera_->disconnected.disconnect(this, &LibcameraCapture::on_disconnected);
    }
    // Off the manager's list: retries find no camera until it is back.
    forget_camera(manager_.get(), camera_);
    // Kept for the life of the process (reachable, never destroyed: even at
    // exit, tearing these down would reach the same assertion).
    {
      std::lock_guard<std::mutex> lock(abandoned_mutex);
      abandoned_cameras().push_back({std::move(requests_), std::move(allocator_),
                                     std::move(config_), std::move(camera_), manager_});
    }
    requests_.clear();
    started_ = acquired_ = connected_ = false;
  }
  if (camera_) {
    if (started_ && !disconnected_) camera_->stop();  // completes every pending request (cancelled)
    started_ = false;
    if (connected_) {
      camera_->requestCompleted.disconnect(this, &LibcameraCapture::on_completed);
      camera_->disconnected.disconnect(this, &LibcameraCapture::on_disconnected);
      connected_ = false;
    }
  }
  requests_.clear();
  for (const Mapping& m : mappings_) munmap(m.base, m.length);
  mappings_.clear();
  if (allocator_ && stream_) allocator_->free(stream_);
  allocator_.reset();
  config_.reset();
  if (camera_ && acquired_) camera_->release();
  acquired_ = false;
  camera_.reset();
  manager_.reset();
  if (event_fd_ >= 0) close(event_fd_);
  event_fd_ = -1;
}

void LibcameraCapture::notify() {
  const uint64_t one = 1;
  if (write(event_fd_, &one, sizeof one) < 0) {
    // Only EAGAIN (the counter is full) is possible: the reader is awake anyway.
  }
}

// libcamera's thread.
void LibcameraCapture::on_completed(lc::Request* request) {
  if (request->status() == lc::Request::RequestCancelled) return;  // stop()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (done_count_ == done_.size()) return;  // cannot happen: one slot per request
    done_[(done_head_ + done_count_) % done_.size()] = request;
    ++done_count_;
  }
  notify();
}

// libcamera's thread: the camera was unplugged (udev saw it go).
void LibcameraCapture::on_disconnected() {
  disconnected_ = true;
  gone_ = true;
  notify();
}

VideoCapture::Result LibcameraCapture::next(VideoFrame& frame, int timeout_ms, int wake_fd) {
  for (;;) {
    bool have = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      have = done_count_ > 0;
    }
    pollfd fds[2] = {{event_fd_, POLLIN, 0}, {wake_fd, POLLIN, 0}};
    int r;
    do r = poll(fds, wake_fd >= 0 ? 2 : 1, have ? 0 : timeout_ms);
    while (r < 0 && errno == EINTR);
    if (r < 0) {
      error_ = std::string("poll: ") + std::strerror(errno);
      return Result::kGone;
    }
    if (wake_fd >= 0 && fds[1].revents) return Result::kWoken;
    if (fds[0].revents) {
      uint64_t count;
      if (read(event_fd_, &count, sizeof count) < 0) {
        // EAGAIN: drained already.
      }
    }
    lc::Request* request = nullptr;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (done_count_ > 0) {
        request = done_[done_head_];
        done_head_ = (done_head_ + 1) % done_.size();
        --done_count_;
      }
    }
    if (request) {
      stalled_ = false;
      const uint64_t i = request->cookie();
      lc::FrameBuffer* fb = request->findBuffer(stream_);
      if (i >= mappings_.size() || !fb) {
        error_ = "libcamera returned a request that is not ours";
        return Result::kGone;
      }
      const lc::FrameMetadata& md = fb->metadata();
      frame.index = static_cast<int>(i);
      frame.data = mappings_[i].data;
      frame.bytes = md.status == lc::FrameMetadata::FrameSuccess && !md.planes().empty()
                        ? std::min<size_t>(md.planes()[0].bytesused, mappings_[i].plane_length)
                        : 0;  // a damaged frame: the caller skips it
      frame.sequence = md.sequence;
      frame.timestamp_ns = static_cast<int64_t>(md.timestamp);
      if (!metadata_seen_) {  // once: copying it every frame would allocate every frame
        last_metadata_ = request->metadata();
        metadata_seen_ = true;
      }
      return Result::kFrame;
    }
    if (gone_) {
      error_ = "the camera was unplugged (libcamera: \"" + id_ + "\" disconnected)";
      return Result::kGone;
    }
    if (r == 0 || !fds[0].revents) {
      stalled_ = true;  // cleared by the next frame
      // No frame for a while: if the camera's nodes are gone from /dev while
      // libcamera was not told, say so now (and stop its thread spinning on
      // them) rather than after more silent timeouts.
      if (!disconnected_ && LibcameraNodes::get().silence_removed() > 0) {
        nodes_removed_ = true;
        gone_ = true;
        LOG_WARN(
            "libcamera: camera \"%s\": its device nodes were removed (unplugged or the driver "
            "unbound) and libcamera was not told: silenced them",
            id_.c_str());
        error_ = "the camera's device nodes were removed (libcamera: \"" + id_ + "\" not told)";
        return Result::kGone;
      }
      return Result::kTimeout;
    }
  }
}

void LibcameraCapture::release(const VideoFrame& frame) {
  if (frame.index < 0 || static_cast<size_t>(frame.index) >= requests_.size() || !started_) return;
  lc::Request* request = requests_[static_cast<size_t>(frame.index)].get();
  request->reuse(lc::Request::ReuseBuffers);
  if (!pending_controls_.empty()) {
    request->controls().merge(pending_controls_);
    pending_controls_.clear();
  }
  if (camera_->queueRequest(request) < 0) {
    // Disconnected or stopped: the next next() without frames reports it.
    gone_ = true;
    notify();
  }
}

std::vector<CaptureControl> LibcameraCapture::controls() {
  std::vector<CaptureControl> out;
  for (const auto& [id, info] : camera_->controls()) {
    const lc::ControlValue& now =
        last_metadata_.contains(id->id()) ? last_metadata_.get(id->id()) : lc::ControlValue();
    out.push_back({id->id(), id->name(), control_json(now), control_json(info.def())});
  }
  std::sort(out.begin(), out.end(),
            [](const CaptureControl& a, const CaptureControl& b) { return a.name < b.name; });
  return out;
}

std::vector<LockedControl> LibcameraCapture::lock_auto(const AutoLockRequest& o) {
  std::vector<LockedControl> out;
  if (o.keep_auto) {
    out.push_back({"auto controls", "left as they were (--keep-auto)"});
    return out;
  }
  const lc::ControlInfoMap& offered = camera_->controls();
  // "Keep the value in use" needs one frame's metadata to read it from.
  if (!metadata_seen_ &&
      (offered.count(&lc::controls::AeEnable) || offered.count(&lc::controls::AwbEnable))) {
    VideoFrame f;
    for (int tries = 0; tries < 3; ++tries) {
      const Result r = next(f, 1000, -1);
      if (r == Result::kFrame) {
        release(f);
        break;
      }
      if (r == Result::kGone) break;
    }
  }
  auto has = [&](const lc::ControlId& id) { return offered.count(&id) > 0; };
  if (!has(lc::controls::AeEnable)) {
    out.push_back({"AeEnable", "not offered"});
  } else {
    pending_controls_.set(lc::controls::AeEnable, false);
    out.push_back({"AeEnable", "off"});
  }
  if (!has(lc::controls::ExposureTime)) {
    out.push_back({"ExposureTime", "not offered"});
  } else if (o.exposure >= 0) {
    pending_controls_.set(lc::controls::ExposureTime, static_cast<int32_t>(o.exposure));
    out.push_back({"ExposureTime", "set to " + std::to_string(o.exposure) + " us"});
  } else if (auto v = last_metadata_.get(lc::controls::ExposureTime)) {
    pending_controls_.set(lc::controls::ExposureTime, *v);
    out.push_back({"ExposureTime", "kept at " + std::to_string(*v) + " us"});
  } else {
    out.push_back({"ExposureTime", "not set: the camera reports no current value"});
  }
  if (!has(lc::controls::AnalogueGain)) {
    out.push_back({"AnalogueGain", "not offered"});
  } else if (o.gain >= 0) {
    pending_controls_.set(lc::controls::AnalogueGain, static_cast<float>(o.gain));
    out.push_back({"AnalogueGain", "set to " + std::to_string(o.gain)});
  } else if (auto v = last_metadata_.get(lc::controls::AnalogueGain)) {
    pending_controls_.set(lc::controls::AnalogueGain, *v);
    out.push_back({"AnalogueGain", "kept at " + control_json(lc::ControlValue(*v))});
  } else {
    out.push_back({"AnalogueGain", "not set: the camera reports no current value"});
  }
  if (!has(lc::controls::AwbEnable)) {
    out.push_back({"AwbEnable", "not offered"});
  } else {
    pending_controls_.set(lc::controls::AwbEnable, false);
    out.push_back({"AwbEnable", "off"});
  }
  if (!has(lc::controls::ColourGains)) {
    out.push_back({"ColourGains", "not offered"});
  } else if (auto v = last_metadata_.get(lc::controls::ColourGains)) {
    const float r = (*v)[0], b = (*v)[1];
    pending_controls_.set(lc::controls::ColourGains, lc::Span<const float, 2>({r, b}));
    char buf[64];
    std::snprintf(buf, sizeof buf, "kept at red %.3f, blue %.3f", static_cast<double>(r),
                  static_cast<double>(b));
    out.push_back({"ColourGains", buf});
  } else {
    out.push_back({"ColourGains", "not set: the camera reports no current value"});
  }
  if (o.white_balance >= 0)
    out.push_back({"white_balance", "not set: libcamera takes colour gains, not a temperature"});
  return out;
}

}  // namespace

std::unique_ptr<VideoCapture> open_libcamera_capture(const CaptureSettings& settings) {
  return std::make_unique<LibcameraCapture>(settings);
}

}  // namespace candela
