#include "sound/sound_settings.h"

#include <cctype>
#include <cstdint>

#include "params/params.h"

namespace candela {

SoundSettings parse_sound(ParamReader& r, bool present) {
  SoundSettings s;
  s.enabled = r.boolean("enabled", present);
  s.volume = static_cast<float>(r.number("volume", s.volume, 0, 1));
  s.device = r.string("device", s.device);
  if (s.device.empty() || s.device.size() > 256)
    r.fail("device",
           "expected an ALSA PCM name (\"default\", \"hw:1,0\", ...) of 1..256 characters");
  for (char c : s.device)
    if (static_cast<unsigned char>(c) < 0x20)
      r.fail("device", "expected an ALSA PCM name without control characters");
  // ALSA's file and tee plugins write the sound to any path the kiosk user
  // can write (690 MB an hour; issue 34): a scene names a sound card.
  std::string plugin = s.device.substr(0, s.device.find(':'));
  for (char& c : plugin) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (plugin == "file" || plugin == "tee")
    r.fail("device",
           "expected a sound card's PCM (\"default\", \"hw:1,0\", ...), not a plugin that writes "
           "a file (\"" +
               plugin + ":\")");
  s.crackle_rate = r.fixed("crackle_rate", s.crackle_rate.to_double(), 0, 200);
  s.pop_rate = r.fixed("pop_rate", s.pop_rate.to_double(), 0, 50);
  s.knock_rate = r.fixed("knock_rate", s.knock_rate.to_double(), 0, 10);
  s.sputter_rate = r.fixed("sputter_rate", s.sputter_rate.to_double(), 0, 50);
  s.roar = static_cast<float>(r.number("roar", s.roar, 0, 4));
  s.crackle = static_cast<float>(r.number("crackle", s.crackle, 0, 4));
  s.whoosh = static_cast<float>(r.number("whoosh", s.whoosh, 0, 4));
  s.candle = static_cast<float>(r.number("candle", s.candle, 0, 4));
  s.buffer_periods = static_cast<int>(r.integer("buffer_periods", s.buffer_periods, 2, 16));
  s.seed = static_cast<uint64_t>(r.integer("seed", 0, 0, INT64_MAX));
  r.finish();
  return s;
}

}  // namespace candela
