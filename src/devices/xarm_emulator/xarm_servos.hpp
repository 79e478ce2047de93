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
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>

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
  std::function<bool(std::span<const double>)> touches;
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
  // invalid_config) if the settings file exists but cannot be read or is corrupt.
  XarmServos(XarmServosOptions options, TimePoint now);

  std::span<const ServoId> servos() const override { return ids_; }
  PositionRange position_range(ServoId servo) const override;
  void advance_to(TimePoint now) override;
  Result<Duration> move(std::span<const ServoTarget> targets, Duration time,
                        TimePoint now) override;
  std::int16_t position(ServoId servo) const override;
  void torque_off(std::span<const ServoId> servos) override;
  void halt(TimePoint now) override;
  std::uint16_t battery_millivolts() const override;
  void adjust_offset(ServoId servo, std::int8_t offset) override;
  Status save_offsets(std::span<const ServoId> servos) override;
  std::int8_t offset(ServoId servo) const override;
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
    BusServoLimits limits;
  };
  Servo& at(ServoId id) { return servos_[id - 1]; }
  const Servo& at(ServoId id) const { return servos_[id - 1]; }
  bool save_settings();
  void load_settings();
  // Where a servo's move has it at `t` (servo mode, torque on).
  double planned(const Servo& s, TimePoint t) const;
  // One step of at most kContactStep against the obstacle.
  void step_against_obstacle(TimePoint t);

  XarmServosOptions options_;
  std::array<ServoId, kServoCount> ids_{1, 2, 3, 4, 5, 6};
  std::array<Servo, kServoCount> servos_;
  ServoId info_servo_ = 1;
  TimePoint now_{};
  std::string last_save_error_;
};

}  // namespace armctl::xarm
