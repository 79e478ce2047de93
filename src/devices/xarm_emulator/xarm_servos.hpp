// The six bus servos of an emulated xArm (IDs 1..6), as an rc_board::ArmBackend.
//
// Model (documented in docs/xarm-emulator.md):
// - Positions 0..1000 over 240 degrees. A move is linear from where the servo is to the
//   target over the asked time, but never faster than kMaxSpeed (0 ms = as fast as it can).
// - Offsets shift the shaft: the servo stands at commanded + offset, and that is what
//   ServoPositionRead reports (so reads can leave 0..1000). Adjust acts at once and is
//   volatile; save writes the current offsets to the state dir, loaded on the next start.
// - Torque off leaves a servo limp where it is (no gravity); its next move restores torque.
// - Motor mode turns the shaft continuously at speed x 1.5 units/s (1000 = one turn/s, a
//   turn being 1500 units), positions wrapping in 0..1499, until a move, torque off or halt.
// - Battery: the configured voltage, sagging kSagPerMovingServo per servo in motion.
// - BusServoInfoRead/Write address one servo: the one last written (servo 1 at start);
//   limits persist in the state dir like a real servo's EEPROM. Writing an ID the arm does
//   not have is refused (re-numbering servos needs a single servo on the bus).
// - Mis-assembled (options' miscal, core/miscalibration.hpp): horns shifted and one servo
//   mounted reversed change only where the arm physically stands (true_position); one servo
//   answering another's ID changes what the bus does (docs/xarm-emulator.md "Mis-assembled"):
//   a command to that ID reaches both servos, a read of it is answered by both at once
//   (bus_replies.hpp: usually no reply), and nobody answers the ID of the servo's place.
//   set_connected() unplugs servos so that IDs can be set one servo at a time.
//
// Places and IDs: the arm has six places for servos, place k where the arm file's servo k
// belongs; the servo mounted there answers ID k unless the miscalibration says otherwise.
// What the Board asks (moves, reads, offsets, torque) goes to IDs, to every connected servo
// answering it; the accessors for tests and tools below (position, offset, torque, moving,
// move_by_hand, true_position...) name places.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/miscalibration.hpp"
#include "devices/rc_board/arm_backend.hpp"

namespace armctl::xarm {

using rc_board::BusServoInfoReply;
using rc_board::BusServoLimits;
using rc_board::PositionRange;
using rc_board::ServoId;
using rc_board::ServoMode;
using rc_board::ServoTarget;

struct XarmServosOptions {
  std::optional<std::filesystem::path> state_dir;  // nothing: settings are not persisted
  std::uint16_t battery_millivolts = 7500;
  std::uint8_t temperature = 35;  // C, reported by BusServoInfoRead
  // Something the arm meets (the scene: `armctl sim xarm --scene`): whether the arm touches
  // it with its servos' shafts at these positions (units, servos 1..6 in order). A servo
  // whose next step would make the arm touch stays where it is, stalled against it, while
  // its move goes on (the others go on moving); it follows again once it can.
  // Checked against the physical arm: the true positions (true_position) with a miscal.
  std::function<bool(std::span<const double>)> touches;
  // Mis-assembled on purpose (`sim?miscal=SEED`); must be for the xArm. Settings are then
  // never loaded from or saved to state_dir: a mis-assembled arm is a fresh one every start
  // and must not leave its IDs in a normal board's state.
  std::optional<Miscalibration> miscal;
};

class XarmServos final : public rc_board::ArmBackend {
 public:
  static constexpr std::size_t kServoCount = 6;
  static constexpr double kMaxSpeed = 1500.0;              // units/s: ~0.16 s per 60 degrees
  static constexpr std::uint16_t kSagPerMovingServo = 60;  // mV
  static constexpr double kMotorUnitsPerSpeed = 1.5;       // units/s per speed unit
  static constexpr int kTurn = 1500;                       // units in 360 degrees
  // With an obstacle (options' touches): servos advance in steps this long, each checked
  // (at kMaxSpeed, 1.5 units: a servo stops within 0.4 degrees of contact).
  static constexpr Duration kContactStep = std::chrono::milliseconds(1);

  // Loads saved offsets and limits from the state dir (if any). Throws ArmctlError(io /
  // invalid_config) if the settings file exists but cannot be read or is corrupt, and
  // (invalid_argument) for a miscalibration of the SCARA.
  XarmServos(XarmServosOptions options, TimePoint now);

  std::span<const ServoId> servos() const override { return ids_; }
  PositionRange position_range(ServoId servo) const override;
  void advance_to(TimePoint now) override;
  Result<Duration> move(std::span<const ServoTarget> targets, Duration time,
                        TimePoint now) override;
  std::int16_t position(ServoId place) const override;  // the servo in that place
  std::optional<std::int16_t> read_position(ServoId servo) const override;
  std::optional<std::int8_t> read_offset(ServoId servo) const override;
  std::optional<BusServoInfoReply> read_bus_servo_info() const override;
  void torque_off(std::span<const ServoId> servos) override;
  void halt(TimePoint now) override;
  std::uint16_t battery_millivolts() const override;
  void adjust_offset(ServoId servo, std::int8_t offset) override;
  Status save_offsets(std::span<const ServoId> servos) override;
  std::int8_t offset(ServoId place) const override;  // the servo in that place
  void set_mode(ServoId servo, ServoMode mode, std::int16_t speed, TimePoint now) override;
  BusServoInfoReply bus_servo_info() const override;
  Status write_bus_servo_info(const BusServoLimits& limits) override;

  // For tests and tools.
  bool torque(ServoId servo) const { return at(servo).torque; }
  bool moving(ServoId servo) const;
  ServoMode mode(ServoId servo) const { return at(servo).mode; }
  std::int8_t saved_offset(ServoId servo) const { return at(servo).saved_offset; }
  double commanded_position(ServoId servo) const { return at(servo).position; }
  void set_battery_millivolts(std::uint16_t mv) { options_.battery_millivolts = mv; }
  // An obstacle holds the servo where it is (moves to it are accepted but it does not
  // follow them): following-error tests.
  void set_blocked(ServoId servo, bool blocked) { at(servo).blocked = blocked; }
  // A hand moving a limp servo (teach tests): it stands at `position` (servo units, the
  // commanded frame). Refused (false) while its torque is on: a powered servo holds.
  bool move_by_hand(ServoId servo, double position);
  // Last error from saving settings (empty if none).
  const std::string& last_save_error() const { return last_save_error_; }

  // What the simulator shows (the user's eyes), for tests that answer a calibration wizard as
  // a user would. The true position of the servo in `place`: the units a well-built arm's
  // servo there (as the shipped arm file describes it) would read at the pose it physically
  // stands in; its reading (position) without a miscalibration. Convert to SI with the shipped
  // arm file's mapping (arm/sim_truth.hpp does, and gives the true tool position).
  double true_position(ServoId place) const;
  // A hand moving the limp servo in `place` until it stands at `true_units`; false (nothing
  // moves) while its torque is on.
  bool move_by_hand_to(ServoId place, double true_units);
  // Unplug (false) or plug in (true) the servo in `place`: an unplugged servo has no power (it
  // goes limp where it stands), hears nothing and answers nothing; plugged in again it stays
  // limp until its next move. With exactly one servo plugged in, BusServoInfoRead/Write reach
  // that servo whatever its ID and Write sets its ID: how IDs are set one servo at a time.
  void set_connected(ServoId place, bool connected);
  bool connected(ServoId place) const { return at(place).connected; }
  // The ID the servo in `place` answers (its EEPROM's).
  ServoId bus_id(ServoId place) const { return at(place).limits.servo; }
  const std::optional<Miscalibration>& miscalibration() const { return options_.miscal; }

 private:
  struct Servo {
    double position = 500;  // commanded frame (without offset), where the servo is now
    double from = 500;
    double target = 500;
    TimePoint start{};
    TimePoint end{};  // moving while now < end
    bool torque = true;
    bool blocked = false;
    ServoMode mode = ServoMode::servo;
    std::int16_t motor_speed = 0;
    std::int8_t offset = 0;
    std::int8_t saved_offset = 0;
    BusServoLimits limits;  // limits.servo: the ID it answers
    bool connected = true;
  };
  Servo& at(ServoId place) { return servos_[place - 1]; }
  const Servo& at(ServoId place) const { return servos_[place - 1]; }
  // The connected servos that answer `id` (usually one; two with a duplicated ID; none for
  // the ID nobody has).
  std::vector<Servo*> answering(ServoId id);
  std::vector<const Servo*> answering(ServoId id) const;
  bool all_connected() const;
  // Whether the arm touches the obstacle with its shafts at these readings (per place).
  bool touching(std::array<double, kServoCount> shafts) const;
  bool save_settings();
  void load_settings();
  // Where a servo's move has it at `t` (servo mode, torque on).
  double planned(const Servo& s, TimePoint t) const;
  // One step of at most kContactStep against the obstacle.
  void step_against_obstacle(TimePoint t);

  XarmServosOptions options_;
  std::array<ServoId, kServoCount> ids_{1, 2, 3, 4, 5, 6};
  std::array<Servo, kServoCount> servos_;
  ServoId info_servo_ = 1;  // the place BusServoInfoRead reports with every servo plugged in
  TimePoint now_{};
  std::string last_save_error_;
};

}  // namespace armctl::xarm
