// The libcamera backend of VideoCapture (Raspberry Pi cameras, vimc). Only
// built when pkg-config finds libcamera (Debian: libcamera-dev); all libcamera
// code lives in libcamera_capture.cpp, so nothing else includes its headers.
#pragma once

#include <memory>

#include "input/video_capture.h"

namespace candela {

// settings.device: a libcamera camera id (`cam -l`) or "auto" (the first
// camera). Asks for the Viewfinder role at the nearest size and a format
// candela reads, and starts the camera. Throws RuntimeError saying what
// failed (no camera, unknown id, busy, no usable format).
std::unique_ptr<VideoCapture> open_libcamera_capture(const CaptureSettings& settings);

}  // namespace candela
