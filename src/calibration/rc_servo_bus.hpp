// The calibration wizard's servo bus (servo_bus.hpp) over a Robot Commands board: reads are
// ServoPositionRead, a new ID is BusServoInfoWrite, offsets are ServoOffsetRead,
// ServoOffsetAdjust and ServoOffsetWrite.
#pragma once

#include "calibration/servo_bus.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::calibration {

class RcServoBus final : public ServoBus {
 public:
  // `client` must outlive this.
  explicit RcServoBus(robot_commands::Client& client) : client_(client) {}

  Result<std::optional<double>> read_position(int id) override;
  Status set_id_of_only_servo(int id) override;
  Result<int> read_offset(int id) override;
  Status adjust_offset(int id, int units) override;
  Status save_offset(int id) override;

 private:
  robot_commands::Client& client_;
};

}  // namespace armctl::calibration
