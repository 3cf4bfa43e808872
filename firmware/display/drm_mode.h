// Which mode to drive a screen with, and whether a hot-plug changed it:
// decisions on the modes a connector lists, no device needed (unit-tested
// in tests/display/drm_mode_test.cpp).
#pragma once

#include <xf86drmMode.h>

#include <cstdint>
#include <string>

#include "display/display.h"

namespace candela {

// The mode to drive a connector listing `modes` (count > 0) with:
// options.width x height (and refresh_hz) where the connector lists it (the
// preferred one among equals, else the highest refresh), else its preferred
// mode (the first if none is marked), with a warning naming what is missing.
// probe_kms_connector chooses with it at start and after every hot-plug, so
// a monitor plugged in with another preferred mode gets that mode.
const drmModeModeInfo& choose_mode(const drmModeModeInfo* modes, int count,
                                   const DisplayOptions& options, const std::string& connector);

// After a hot-plug event and probe_kms_connector: whether the screen is set up
// afresh (surfaces of the new size, the mode set with the next frame): when
// none was driven, or another connector or another mode was chosen (a monitor
// unplugged and another plugged in). False: the same screen, nothing to do.
bool needs_new_mode(bool had_screen, uint32_t old_connector, const drmModeModeInfo& old_mode,
                    uint32_t connector, const drmModeModeInfo& mode);

std::string describe_mode(const drmModeModeInfo& mode);

}  // namespace candela
