#include "apps/armctl/jog_gamepad.hpp"

#include "core/error.hpp"
#include "core/printable.hpp"
#include "jog/evdev_gamepad.hpp"
#include "jog/gamepad_feed.hpp"
#include "jog/gamepad_jog.hpp"
#include "jog/gamepad_replay.hpp"

namespace armctl::cli {
namespace {

class GamepadDriver final : public JogDriver {
 public:
  GamepadDriver(const arm::ArmModel& model, std::unique_ptr<jog::GamepadSource> source)
      : pad_(model), source_(std::move(source)) {}

  std::vector<std::string> intro() const override { return {source_->description(), pad_.help(), pad_.describe()}; }

  void cycle(TimePoint now, arm::ServoInput& input, const Say& say) override {
    for (const std::string& line : jog::feed_gamepad(*source_, pad_, input, now)) say(line);
  }

  std::string describe() const override {
    if (!pad_.connected()) return pad_.describe() + " | no gamepad";
    return pad_.describe() + (pad_.deadman() ? "" : " | dead-man released");
  }

 private:
  jog::GamepadJog pad_;
  std::unique_ptr<jog::GamepadSource> source_;
};

}  // namespace

std::unique_ptr<JogDriver> gamepad_driver(const arm::ArmModel& model, const std::string& device,
                                          const std::string& replay) {
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
  return std::make_unique<GamepadDriver>(model, std::move(source));
}

}  // namespace armctl::cli
