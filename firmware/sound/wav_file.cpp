#include "sound/wav_file.h"

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace candela {
namespace {
void put16(unsigned char* p, uint32_t v) {
  p[0] = static_cast<unsigned char>(v);
  p[1] = static_cast<unsigned char>(v >> 8);
}
void put32(unsigned char* p, uint32_t v) {
  put16(p, v & 0xffff);
  put16(p + 2, v >> 16);
}
}  // namespace

WavFile::WavFile(const std::string& path, int rate, int channels)
    : path_(path), rate_(rate), channels_(channels) {
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw RuntimeError(path + ": cannot write the sound: " + std::strerror(errno));
  std::setvbuf(f_, buffer_, _IOFBF, sizeof buffer_);
  header(0);
}

WavFile::~WavFile() {
  if (f_) std::fclose(f_);
}

void WavFile::header(uint32_t data_bytes) {
  unsigned char h[44];
  std::memcpy(h, "RIFF", 4);
  put32(h + 4, 36 + data_bytes);
  std::memcpy(h + 8, "WAVEfmt ", 8);
  put32(h + 16, 16);
  put16(h + 20, 1);  // PCM
  put16(h + 22, static_cast<uint32_t>(channels_));
  put32(h + 24, static_cast<uint32_t>(rate_));
  put32(h + 28, static_cast<uint32_t>(rate_ * channels_ * 2));
  put16(h + 32, static_cast<uint32_t>(channels_ * 2));
  put16(h + 34, 16);
  std::memcpy(h + 36, "data", 4);
  put32(h + 40, data_bytes);
  if (std::fwrite(h, 1, sizeof h, f_) != sizeof h)
    throw RuntimeError(path_ + ": writing the sound failed: " + std::strerror(errno));
}

void WavFile::write(const int16_t* s, size_t frames) {
  // Little-endian on every target Candela builds for (x86-64, arm64).
  const size_t n = frames * static_cast<size_t>(channels_);
  if (std::fwrite(s, sizeof(int16_t), n, f_) != n)
    throw RuntimeError(path_ + ": writing the sound failed: " + std::strerror(errno));
  frames_ += frames;
}

void WavFile::close() {
  if (!f_) return;
  const uint64_t bytes = frames_ * static_cast<uint64_t>(channels_) * 2;
  bool ok = std::fflush(f_) == 0 && std::fseek(f_, 0, SEEK_SET) == 0;
  if (ok) {
    header(static_cast<uint32_t>(bytes > 0xFFFFFFD0ULL ? 0xFFFFFFD0ULL : bytes));
    ok = std::fflush(f_) == 0;
  }
  const int err = errno;
  ok = (std::fclose(f_) == 0) && ok;
  f_ = nullptr;
  if (!ok) throw RuntimeError(path_ + ": writing the sound failed: " + std::strerror(err));
}

}  // namespace candela
