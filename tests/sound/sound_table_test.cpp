// The scene's [sound] table: validated like every other table (file, key,
// what was expected); without it a scene is silent.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "scene/scene_file.h"

namespace candela {
namespace {

std::string error_of(const std::string& text) {
  try {
    load_scene_text(text, "room.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SoundTable, AbsentMeansSilent) {
  EXPECT_FALSE(load_scene_text("seed = 2\n", "room.toml").sound.enabled);
}

TEST(SoundTable, PresentMeansOnWithDefaults) {
  const SceneDesc d = load_scene_text("[sound]\n", "room.toml");
  EXPECT_TRUE(d.sound.enabled);
  EXPECT_EQ(d.sound.device, "default");
  EXPECT_FLOAT_EQ(d.sound.volume, 0.6f);
  EXPECT_EQ(d.sound.buffer_periods, 3);
}

TEST(SoundTable, ReadsEveryKey) {
  const SceneDesc d = load_scene_text(R"([sound]
enabled = true
volume = 0.25
device = "plughw:CARD=vc4hdmi0,DEV=0"
crackle_rate = 9.5
pop_rate = 1
knock_rate = 0.1
sputter_rate = 4
roar = 2
crackle = 0.5
whoosh = 0
candle = 3
buffer_periods = 4
seed = 12
)",
                                      "room.toml");
  const SoundSettings& s = d.sound;
  EXPECT_TRUE(s.enabled);
  EXPECT_FLOAT_EQ(s.volume, 0.25f);
  EXPECT_EQ(s.device, "plughw:CARD=vc4hdmi0,DEV=0");
  EXPECT_EQ(s.crackle_rate, Fixed::from_ratio(19, 2));
  EXPECT_EQ(s.pop_rate, Fixed::from_int(1));
  EXPECT_EQ(s.knock_rate, Fixed::from_ratio(1, 10));
  EXPECT_EQ(s.sputter_rate, Fixed::from_int(4));
  EXPECT_FLOAT_EQ(s.roar, 2.0f);
  EXPECT_FLOAT_EQ(s.crackle, 0.5f);
  EXPECT_FLOAT_EQ(s.whoosh, 0.0f);
  EXPECT_FLOAT_EQ(s.candle, 3.0f);
  EXPECT_EQ(s.buffer_periods, 4);
  EXPECT_EQ(s.seed, 12u);
  EXPECT_FALSE(load_scene_text("[sound]\nenabled = false\n", "room.toml").sound.enabled);
}

TEST(SoundTable, BadValuesNameFileKeyAndWhatWasExpected) {
  EXPECT_EQ(error_of("[sound]\nvolume = 2\n"),
            "room.toml: sound.volume: expected a number in [0, 1], got 2");
  EXPECT_EQ(error_of("[sound]\ncrackle_rate = -1\n"),
            "room.toml: sound.crackle_rate: expected a number in [0, 200], got -1");
  EXPECT_EQ(error_of("[sound]\nbuffer_periods = 1\n").rfind("room.toml: sound.buffer_periods: ", 0),
            0u);
  EXPECT_NE(error_of("[sound]\ndevice = 3\n").find("room.toml: sound.device: expected a string"),
            std::string::npos)
      << error_of("[sound]\ndevice = 3\n");
  EXPECT_EQ(
      error_of("[sound]\ndevice = \"\"\n").rfind("room.toml: sound.device: expected an ALSA", 0),
      0u);
  EXPECT_NE(error_of("[sound]\nvolum = 0.5\n").find("room.toml: sound.volum: unknown key"),
            std::string::npos);
  EXPECT_EQ(error_of("sound = 1\n"), "room.toml: sound: expected a table, got 1");
  // Issue 34: ALSA's file and tee plugins wrote 559 MB in 6 s to any path.
  EXPECT_EQ(error_of("[sound]\ndevice = \"file:'/tmp/x',raw\"\n"),
            "room.toml: sound.device: expected a sound card's PCM (\"default\", \"hw:1,0\", ...), "
            "not a plugin that writes a file (\"file:\")");
  EXPECT_EQ(error_of("[sound]\ndevice = \"TEE:default,'/tmp/x'\"\n")
                .rfind("room.toml: sound.device: expected a sound card's PCM", 0),
            0u);
  EXPECT_EQ(error_of("[sound]\ndevice = \"hw:1,0\"\n"), "");
  EXPECT_EQ(error_of("[sound]\nenabled = \"yes\"\n").rfind("room.toml: sound.enabled: ", 0), 0u);
}

}  // namespace
}  // namespace candela
