#include "apps/armctl/jog_gamepad.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/printable.hpp"
#include "jog/evdev_gamepad.hpp"
#include "jog/gamepad_feed.hpp"
#include "jog/gamepad_jog.hpp"
#include "jog/gamepad_recorder.hpp"
#include "jog/gamepad_replay.hpp"

namespace armctl::cli {
namespace {

class GamepadDriver final : public JogDriver {
 public:
  GamepadDriver(const arm::ArmModel& model, std::unique_ptr<jog::GamepadSource> source, jog::GamepadRecorder* recorder,
                std::string record)
      : pad_(model), source_(std::move(source)), recorder_(recorder), record_(std::move(record)) {}

  std::vector<std::string> intro() const override { return {source_->description(), pad_.help(), pad_.describe()}; }

  void cycle(TimePoint now, arm::ServoInput& input, const Say& say) override {
    for (const std::string& line : jog::feed_gamepad(*source_, pad_, input, now)) say(line);
  }

  void after(const Say& say) override {
    if (!recorder_) return;
    if (Status s = recorder_->save(record_); !s) say("not recorded: " + s.error().message);
    else say("recorded the gamepad in " + printable(record_));
  }

  std::string describe() const override {
    if (!pad_.connected()) return pad_.describe() + " | no gamepad";
    return pad_.describe() + (pad_.deadman() ? "" : " | dead-man released");
  }

 private:
  jog::GamepadJog pad_;
  std::unique_ptr<jog::GamepadSource> source_;
  jog::GamepadRecorder* recorder_;  // in source_, when recording
  std::string record_;
};

}  // namespace

std::unique_ptr<JogDriver> gamepad_driver(const arm::ArmModel& model, const std::string& device,
                                          const std::string& replay, const std::string& record) {
  std::unique_ptr<jog::GamepadSource> source;
  if (!replay.empty()) {
    auto recording = jog::read_pad_recording(replay);
    if (!recording) throw ArmctlError(recording.error());
    source = std::make_unique<jog::GamepadReplay>(std::move(*recording), "the recording " + printable(replay));
  } else {
    auto pad = jog::EvdevGamepad::open(device);
    if (!pad) throw ArmctlError(pad.error());
    source = std::move(*pad);
  }
  jog::GamepadRecorder* recorder = nullptr;
  if (!record.empty()) {
    // Refused before the session rather than losing it at the end.
    if (Status s = check_writable(record); !s) throw ArmctlError(s.error());
    auto wrapped = std::make_unique<jog::GamepadRecorder>(std::move(source));
    recorder = wrapped.get();
    source = std::move(wrapped);
  }
  return std::make_unique<GamepadDriver>(model, std::move(source), recorder, record);
}

}  // namespace armctl::cli
