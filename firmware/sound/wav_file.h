// A 16-bit PCM .wav file, written as it goes; the RIFF sizes are patched at
// close(). Throws RuntimeError naming the path on any I/O failure.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace candela {

class WavFile {
 public:
  WavFile(const std::string& path, int sample_rate, int channels);
  ~WavFile();
  WavFile(const WavFile&) = delete;
  WavFile& operator=(const WavFile&) = delete;
  void write(const int16_t* samples, size_t frames);
  void close();
  uint64_t frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  void header(uint32_t data_bytes);
  std::string path_;
  int rate_, channels_;
  FILE* f_ = nullptr;
  uint64_t frames_ = 0;
  char buffer_[1 << 16];  // stdio's buffer, ours: nothing allocated while writing
};

}  // namespace candela
