// A simple DC joint for loop tests: first-order speed response to PWM duty, optional
// constant load (as a speed offset, like gravity on Z), optional stall; it feeds exact 4x
// quadrature edges into the JointController. Test-only, so it may use double.
#pragma once

#include <cmath>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus::testing {

class MotorPlant {
 public:
  double no_load_cps = 25000.0;  // clicks/s at full duty
  double tau_s = 0.020;          // mechanical time constant
  double load_cps = 0.0;         // constant speed lost to a load (sign: pulls toward -)
  bool stalled = false;          // a blocked joint: never moves
  // Wiring: false = the original boards' (bridge duty > 0, the "right" input D11, counts
  // the encoder up); true = motor leads swapped (D11 counts down).
  bool leads_swapped = false;
  int16_t pwm_max = 255;

  // One 1 ms control period: tick the controller, then integrate the motor for 1 ms.
  DriveOutput step(JointController& joint) {
    const DriveOutput out = joint.control_tick();
    const double sign = leads_swapped ? -1.0 : 1.0;
    const double drive = out.enable ? sign * no_load_cps * out.duty / pwm_max : 0.0;
    const int substeps = 10;
    const double dt = 0.001 / substeps;
    for (int i = 0; i < substeps; ++i) {
      if (stalled) {
        speed_cps_ = 0.0;
      } else {
        speed_cps_ += (drive - load_cps - speed_cps_) * dt / tau_s;
        position_ += speed_cps_ * dt;
      }
      const auto whole = static_cast<int32_t>(std::floor(position_));
      if (whole != emitted_) {
        encoder_.move(joint, whole - emitted_);
        emitted_ = whole;
      }
    }
    return out;
  }
  double position() const { return position_; }
  double speed_cps() const { return speed_cps_; }
  // Move the joint by hand (loop off).
  void push(JointController& joint, int32_t clicks) {
    position_ += clicks;
    encoder_.move(joint, clicks);
    emitted_ += clicks;
  }

 private:
  double position_ = 0.0;
  double speed_cps_ = 0.0;
  int32_t emitted_ = 0;
  EncoderDriver encoder_;
};

}  // namespace armctl::joint_bus::testing
