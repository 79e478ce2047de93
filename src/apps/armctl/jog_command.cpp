// armctl jog [--arm A] [--device URI] [--scene FILE] [--speed F]
//            [--gamepad [auto|/dev/input/eventN] [--record-gamepad FILE] | --gamepad-replay FILE]
// Drives the arm while keys are held (docs/servo.md) or a gamepad's sticks are pushed with
// its dead-man held (docs/gamepad.md): the input becomes servo commands (jog/key_jog.hpp,
// jog/gamepad_jog.hpp) that the servo mode follows (arm/run_servo.hpp), slowing near the
// ends of the joints' ranges, singularities and what the scene holds. The session itself
// (status line, the end at rest) is apps/armctl/jog_session.hpp.
#include <memory>
#include <string>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/jog_gamepad.hpp"
#include "apps/armctl/jog_session.hpp"
#include "apps/armctl/raw_terminal.hpp"
#include "apps/armctl/scene_option.hpp"
#include "jog/key_jog.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

namespace {

struct JogArgs {
  std::string arm = "xarm";
  std::string device;
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  double speed = 1.0;
  std::string gamepad;  // "auto" or /dev/input/eventN
  std::string gamepad_replay;
  std::string record_gamepad;
};

// The keyboard: space stops, Esc, x or Ctrl-C end the session.
class KeyboardDriver final : public JogDriver {
 public:
  explicit KeyboardDriver(const arm::ArmModel& model) : keys_(model) {}
  std::vector<std::string> intro() const override { return {keys_.help(), keys_.describe()}; }
  void cycle(TimePoint now, arm::ServoInput& input, const Say& say) override {
    for (const jog::Key& k : jog::decode_keys(terminal_.read_available()))
      if (auto line = keys_.press(k, now)) say(*line);
    // A pipe that ended ends the session once its last key is let go.
    if (keys_.quit() || (terminal_.ended() && !keys_.moving(now))) {
      input.finish();
      return;
    }
    (void)input.send(keys_.command(now));  // built from the arm's own model: always valid
  }
  std::string describe() const override { return keys_.describe(); }

 private:
  jog::KeyJog keys_;
  RawTerminal terminal_;
};

void run_jog(const JogArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  arm::Arm& arm = *s->arm;
  std::unique_ptr<JogDriver> driver;
  if (a.gamepad.empty() && a.gamepad_replay.empty()) driver = std::make_unique<KeyboardDriver>(arm.model());
  else driver = gamepad_driver(arm.model(), a.gamepad, a.gamepad_replay, a.record_gamepad);
  run_jog_session(arm, *driver, a.speed);
}

}  // namespace

void add_jog_command(CLI::App& app) {
  auto a = std::make_shared<JogArgs>();
  auto* cmd = app.add_subcommand(
      "jog", "Drive the arm from the keyboard while keys are held, or from a gamepad (docs/servo.md, docs/gamepad.md)");
  add_arm_options(cmd, a->arm, a->device);
  add_scene_option(cmd, a->scene);
  cmd->add_option("--speed", a->speed, "Fraction of every joint's velocity limit (0..1, default 1)");
  auto* pad = cmd->add_option("--gamepad", a->gamepad,
                              "Drive from a gamepad: 'auto' (the default: the first found, picked up when plugged "
                              "in) or /dev/input/eventN (docs/gamepad.md)")
                  ->expected(0, 1);
  cmd->add_option("--gamepad-replay", a->gamepad_replay,
                  "Drive from a recorded gamepad event stream (docs/gamepad.md \"Recordings\")")
      ->excludes(pad);
  cmd->add_option("--record-gamepad", a->record_gamepad,
                  "With --gamepad: write what the pad did to FILE, for --gamepad-replay (docs/gamepad.md)")
      ->needs(pad);
  cmd->callback([a, pad] {
    if (pad->count() > 0 && a->gamepad.empty()) a->gamepad = "auto";  // --gamepad without a value
    run_jog(*a);
  });
}

}  // namespace armctl::cli
