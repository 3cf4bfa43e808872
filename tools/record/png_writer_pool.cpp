#include "png_writer_pool.h"

#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>

#include "core/image.h"

namespace candela::record {

PngWriterPool::PngWriterPool(std::string frames_dir, int width, int height, int channels, int slots,
                             int threads, WriteFn write)
    : frames_dir_(std::move(frames_dir)),
      write_(std::move(write)),
      slots_(static_cast<size_t>(std::max(2, slots))) {
  if (!write_)
    write_ = [width, height, channels](const std::string& path, const FrameSlot& s) {
      write_png(path, width, height, channels, s.pixels.data());
    };
  free_.reserve(slots_.size());
  for (auto& s : slots_) {
    s.pixels.resize(static_cast<size_t>(width) * height * channels);
    free_.push_back(&s);
  }
  for (int i = 0; i < std::max(1, threads); ++i) threads_.emplace_back([this] { run(); });
}

PngWriterPool::~PngWriterPool() { close(); }

std::string PngWriterPool::file_name(uint32_t sequence) {
  char name[32];
  std::snprintf(name, sizeof name, "%08u.png", sequence);
  return name;
}

FrameSlot* PngWriterPool::acquire() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (free_.empty()) return nullptr;
  FrameSlot* s = free_.back();
  free_.pop_back();
  return s;
}

void PngWriterPool::give_back(FrameSlot* slot) {
  std::lock_guard<std::mutex> lock(mutex_);
  free_.push_back(slot);
}

void PngWriterPool::submit(FrameSlot* slot) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.push_back(slot);
  work_.notify_one();
}

void PngWriterPool::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
    work_.notify_all();
  }
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

WriteFailure PngWriterPool::classify(const std::exception& e, size_t frame_bytes) const {
  WriteFailure f{e.what(), OutputFault::kOther};
  if (dynamic_cast<const OutputError*>(&e)) {
    if (const OutputFault fault = fault_of(e); fault != OutputFault::kNone) f.fault = fault;
    return f;
  }
  // libpng reports a failed fwrite as "Write Error" without errno: ask the filesystem.
  struct statvfs vfs {};
  if (statvfs(frames_dir_.c_str(), &vfs) != 0) return f;
  const double free_bytes = static_cast<double>(vfs.f_bavail) * vfs.f_bsize;
  if (free_bytes < 2.0 * frame_bytes + 65536) {
    f.fault = OutputFault::kDiskFull;
    f.message = "No space left on device (" +
                std::to_string(static_cast<unsigned long long>(vfs.f_bavail) * vfs.f_bsize / 1024) +
                " KiB free): " + f.message;
  } else if (vfs.f_flag & ST_RDONLY) {
    f.fault = OutputFault::kReadOnly;
  }
  return f;
}

void PngWriterPool::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    work_.wait(lock, [&] { return closing_ || !pending_.empty(); });
    if (pending_.empty()) return;
    FrameSlot* s = pending_.front();
    pending_.pop_front();
    const bool skip = static_cast<bool>(failure_);  // after a failure, write nothing more
    lock.unlock();
    WriteFailure error;
    if (!skip) {
      try {
        write_(frames_dir_ + "/" + file_name(s->sequence), *s);
      } catch (const std::exception& e) {
        error = classify(e, s->pixels.size());
      }
    }
    lock.lock();
    if (!skip && !error) written_[s->sequence] = {s->sequence, s->timestamp_ns};
    if (error && !failure_) failure_ = error;
    free_.push_back(s);
  }
}

std::vector<WrittenFrame> PngWriterPool::written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<WrittenFrame> out;
  out.reserve(written_.size());
  for (const auto& [seq, w] : written_) out.push_back(w);
  return out;
}

size_t PngWriterPool::written_count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_.size();
}

double PngWriterPool::measured_fps() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (written_.size() < 10) return 0;
  const auto& first = written_.begin()->second;
  const auto& last = written_.rbegin()->second;
  const double span = static_cast<double>(last.timestamp_ns - first.timestamp_ns) * 1e-9;
  const double periods = static_cast<double>(last.sequence - first.sequence);
  return span > 0 ? periods / span : 0;
}

WriteFailure PngWriterPool::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

}  // namespace candela::record
