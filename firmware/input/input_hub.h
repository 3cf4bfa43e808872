// The runtime's inputs: GPIO sensors and the control socket on one input
// thread (asleep in poll()), the camera on its own thread, the display's keys
// on the frame loop's, each handing wind events to the frame loop through a
// lock-free SPSC queue. The frame loop
// calls drain() once per frame (applies the events to the wind field) and
// publish() once per frame (what `state` reports). Nothing here ever blocks
// or allocates on the frame loop's side.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "display/display.h"
#include "input/input_event.h"
#include "input/spsc_queue.h"
#include "scene/input_spec.h"
#include "wind/wind_field.h"

namespace candela {

struct ControlCommand;
class GpioSource;
class ControlServer;
class CameraSource;
class KioskControl;

class InputHub {
 public:
  // `control_path` empty: no control socket.
  InputHub(std::vector<InputSpec> inputs, const WindSpec& wind, std::string control_path = {});
  ~InputHub();
  InputHub(const InputHub&) = delete;
  InputHub& operator=(const InputHub&) = delete;

  // Starts the threads. Missing hardware is logged and retried, never thrown;
  // a control socket that cannot be made is logged and left out.
  void start();
  void stop();
  bool control_ready() const { return control_ != nullptr; }

  // Frame loop: a key the display delivered (input/key_input.h says which
  // wind each stands for), applied by the next drain().
  void on_key(Key key);
  // Frame loop, once per frame before the steps: applies queued events.
  void drain(WindField& wind);
  // Frame loop, once per frame after the steps: what `state` reports.
  // candles_lit: -1 when the scene has no candles (reported as null).
  void publish(uint64_t step, uint64_t frame, WindSample wind, int candles_lit = -1);

  // The `state` reply (one JSON line). Input thread.
  std::string state_json() const;
  // What any thread may read (atomics only): frame, wind, volume, candles
  // lit, events. MQTT's retained state.
  std::string summary_json() const;
  // Where a command line came from: each origin has its own lock-free queue
  // to the frame loop (one producer each).
  enum class Origin { kControlSocket, kMqtt };
  // One control command line -> one reply line; the one parser for the
  // control socket (input thread) and MQTT (its client thread).
  std::string answer(std::string_view line, Origin origin = Origin::kControlSocket);

  // The master sound volume, 0..1 (any thread; an atomic): the [sound]
  // volume at start, then what `volume` commands set. The frame loop puts it
  // into every step's SoundCue; the synthesiser glides to it.
  void set_volume(float v) { volume_.store(v, std::memory_order_relaxed); }
  float volume() const { return volume_.load(std::memory_order_relaxed); }

  // The kiosk's commands (scene, brightness, screen, reload, schedule) and
  // what `state` says of it; without one those commands answer an error.
  // Set before start().
  void set_kiosk(KioskControl* kiosk) { kiosk_ = kiosk; }

  uint64_t events_applied() const { return applied_.load(std::memory_order_relaxed); }

  // Several screens, one room (input/room.h): this display stands at (x, z)
  // m. Set before start(); without it nothing goes to or comes from the room.
  void enable_room(double x, double z);
  bool room_enabled() const { return room_; }
  const WindSpec& wind_spec() const { return wind_spec_; }
  // A gust started here (any input but the room), for the MQTT thread to
  // publish: t_ns is CLOCK_REALTIME when it entered this wind field.
  struct RoomOut {
    WindEvent wind;
    int64_t t_ns = 0;
  };
  // A gust from another display, already attenuated, to start in this wind
  // field at due_mono_ns (CLOCK_MONOTONIC, the frame loop's clock).
  struct RoomIn {
    WindEvent wind;
    int64_t due_mono_ns = 0;
    // CLOCK_REALTIME: left the origin, received here, due here.
    int64_t origin_ns = 0, received_ns = 0, due_ns = 0;
  };
  // MQTT thread only.
  bool take_room_gust(RoomOut& out) { return room_out_.pop(out); }
  bool give_room_gust(const RoomIn& in);
  enum class RoomNote { kSent, kReceived, kLate, kOwn, kInvalid, kUpwind };
  void room_note(RoomNote n) {
    room_counts_[static_cast<int>(n)].fetch_add(1, std::memory_order_relaxed);
  }

 private:
  class QueueSink;
  void input_thread();
  std::string answer_command(const ControlCommand& c, Origin origin);

  std::vector<InputSpec> specs_;
  WindSpec wind_spec_;
  std::string control_path_;
  std::vector<std::unique_ptr<GpioSource>> gpio_;
  std::vector<int> gpio_of_spec_;  // index into gpio_, -1 for the camera
  std::unique_ptr<ControlServer> control_;
  std::unique_ptr<CameraSource> camera_;
  SpscQueue<InputEvent, 256> input_queue_;  // producer: the input thread
  SpscQueue<InputEvent, 64> camera_queue_;  // producer: the camera thread
  SpscQueue<InputEvent, 64> mqtt_queue_;    // producer: the MQTT client thread
  SpscQueue<InputEvent, 64> key_queue_;     // producer: the frame loop (keys)
  std::unique_ptr<QueueSink> input_sink_;
  std::unique_ptr<QueueSink> camera_sink_;
  std::unique_ptr<QueueSink> key_sink_;
  int stop_fd_ = -1;
  std::thread thread_;

  // Written by the frame loop, read by the input thread.
  std::atomic<uint64_t> step_{0}, frame_{0}, applied_{0};
  std::atomic<int32_t> wind_x_{0}, wind_z_{0}, candles_lit_{-1};
  std::atomic<int64_t> last_latency_ns_{-1}, max_latency_ns_{-1};
  std::unique_ptr<std::atomic<uint64_t>[]> applied_by_source_;
  std::atomic<uint64_t> applied_control_{0};
  std::atomic<float> volume_{0.6f};

  // The room: queues each way, the received gusts waiting for their time
  // (frame loop only), what `state` reports.
  void drain_room(WindField& wind);
  bool room_ = false;
  double room_x_ = 0, room_z_ = 0;
  SpscQueue<RoomOut, 64> room_out_;  // producer: the frame loop
  SpscQueue<RoomIn, 64> room_in_;    // producer: the MQTT client thread
  static constexpr int kRoomPending = 32;
  std::array<RoomIn, kRoomPending> room_pending_{};
  int room_pending_n_ = 0;
  int64_t room_last_drain_ns_ = 0;
  std::array<std::atomic<uint64_t>, 6> room_counts_{};
  std::atomic<uint64_t> room_applied_{0}, room_overflow_{0};
  std::atomic<int64_t> room_sent_ns_{0}, room_origin_ns_{0}, room_received_ns_{0}, room_due_ns_{0},
      room_applied_ns_{0}, room_frame_before_ns_{0};
  std::atomic<int> room_waiting_{0};
  KioskControl* kiosk_ = nullptr;
};

}  // namespace candela
