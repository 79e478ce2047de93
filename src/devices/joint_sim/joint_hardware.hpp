// The simulated hardware of one joint: H-bridge -> 24 V DC motor -> gearbox -> load, with a
// quadrature encoder on the motor shaft and optional end stops. PWM duty and enable go in;
// encoder edges (A/B levels with their times) come out. Used by SimJoint (portable
// JointController) and by the emulated ATmega328P joints (devices/joint_avr) alike.
//
// Model (docs/simulator.md has the derivation and the parameter table):
//   H-bridge   enabled: motor voltage V = duty/pwm_max * supply (averaged PWM; duty 0 brakes)
//              disabled: motor terminals open, current 0, the joint coasts
//   motor      i = (V - k*w)/R (inductance neglected: L/R << mechanical time constant)
//   mechanics  J dw/dt = k*i - b*w - Tc*sign(w),  J = J_rotor + J_load/N^2 (motor side)
//              at w = 0 the joint stays stuck while |drive torque| <= Tc (Coulomb friction)
//   encoder    clicks = 4 * lines_per_rev * motor revolutions (4x quadrature decoding)
//   end stops  inelastic: position clamped, w := 0, stuck while pushed into the stop
// Between drive changes the ODE is linear with constant coefficients, so it is integrated
// exactly (exponential solution), split at velocity zero crossings where friction changes
// sign. The exact solution is sampled on a fixed grid of `step` to place encoder edges in
// time (linear interpolation inside one step); a resting joint costs nothing per step.
#pragma once

#include <cstdint>
#include <optional>

#include "core/clock.hpp"

namespace armctl::joint_sim {

struct MotorParams {
  double supply_v = 24.0;
  double resistance_ohm = 2.0;
  double torque_constant_nm_per_a = 0.075;  // equals the back-EMF constant in V*s/rad (SI)
  double rotor_inertia_kgm2 = 5e-5;
  double viscous_friction_nms = 2e-5;  // motor side, N*m per rad/s
  double coulomb_friction_nm = 0.01;   // motor side
};

struct EndStops {
  std::int32_t min_clicks;
  std::int32_t max_clicks;
};

struct JointHardwareParams {
  MotorParams motor;
  double load_inertia_kgm2 = 0.0;  // joint (output) side; reflected through the gearbox
  std::uint32_t gear_numerator = 2448;
  std::uint32_t gear_denominator = 121;
  std::uint32_t encoder_lines_per_rev = 125;  // motor revolution; clicks = 4 x lines
  std::optional<EndStops> end_stops;
  std::int16_t pwm_max = 255;
  // Wiring of the motor leads: false = as the original boards are wired (the H-bridge's
  // "right" input D11, duty > 0, turns the motor the way that counts the encoder up);
  // true = leads swapped (duty > 0 counts down).
  bool leads_swapped = false;
  // Grid for placing encoder edges in time and detecting end-stop contact (the motion itself
  // is exact whatever the step). 1 ms suits the portable controller, which samples the count
  // at its 1 kHz tick; emulated chips that time edges to the microsecond want <= 50 us.
  Duration step = std::chrono::microseconds(1000);

  double gear_ratio() const { return double(gear_numerator) / double(gear_denominator); }
  double clicks_per_motor_rev() const { return 4.0 * encoder_lines_per_rev; }
  // Motor-side inertia seen by the motor.
  double total_inertia_kgm2() const {
    return motor.rotor_inertia_kgm2 + load_inertia_kgm2 / (gear_ratio() * gear_ratio());
  }
};

// Receives encoder edges in time order. a/b are the channel levels after the edge.
class EncoderEdgeSink {
 public:
  virtual ~EncoderEdgeSink() = default;
  virtual void on_encoder_edge(bool a, bool b, TimePoint t) = 0;
};

class JointHardware {
 public:
  explicit JointHardware(const JointHardwareParams& params, TimePoint start = TimePoint{});

  // H-bridge inputs from now on. duty in [-pwm_max, pwm_max] (clamped); > 0 drives the
  // "right" input (D11), which counts the encoder up unless leads_swapped.
  void set_drive(std::int16_t duty, bool enable);
  // Same with duty as a fraction of full scale in [-1, 1] (for PWM read off timer registers).
  void set_drive_fraction(double duty, bool enable);

  // Integrate up to t (no-op if t <= time()), reporting every encoder edge to `sink` (may be
  // null) in order.
  void advance_to(TimePoint t, EncoderEdgeSink* sink);

  TimePoint time() const { return now_; }
  const JointHardwareParams& params() const { return p_; }

  double motor_velocity_rad_s() const { return w_; }
  double motor_angle_rad() const { return theta_; }
  double joint_velocity_clicks_s() const { return w_ * clicks_per_rad_; }
  double position_clicks() const { return theta_ * clicks_per_rad_; }
  double current_a() const;
  double motor_voltage_v() const { return enabled_ ? voltage_ : 0.0; }
  // Integer click count of the encoder (the value a perfect 4x decoder would hold).
  std::int64_t encoder_count() const { return count_; }
  bool encoder_a() const;
  bool encoder_b() const;
  bool at_end_stop() const { return stop_ != 0; }
  bool resting() const { return w_ == 0.0 && stuck_; }

  // Test hooks: put the joint in a state (e.g. spinning) without driving it there.
  void set_motor_velocity(double w_rad_s);
  // An obstacle: the joint's travel becomes min..max clicks (as hard end stops), e.g. a
  // joint held back where it stands (following-error tests).
  void set_end_stops(EndStops stops);
  // A hand turning the joint (teach tests): it is `clicks` further on at once, at rest, the
  // encoder edges sent to `sink` on the way. SimJoint::turn_by_hand checks that the loop is off.
  void turn_by_hand(double clicks, EncoderEdgeSink* sink);

 private:
  struct Coefficients {
    double lambda;  // 1/time constant, 1/s
    double alpha;   // constant acceleration term, rad/s^2
  };
  Coefficients coefficients(int direction) const;
  double drive_torque_at_rest() const;
  void update_stuck();
  void integrate(double dt, Coefficients c, double* w, double* theta) const;
  // expm1(-lambda*step) for the enabled and disabled bridge, so a full step costs no exp().
  double step_decay(bool enabled) const { return enabled ? decay_enabled_ : decay_disabled_; }
  void emit_edges(double theta0, double theta1, TimePoint t0, TimePoint t1,
                  EncoderEdgeSink* sink);

  JointHardwareParams p_;
  double inertia_;
  double clicks_per_rad_;
  double step_s_;
  double stop_min_rad_ = 0.0;
  double stop_max_rad_ = 0.0;
  double decay_enabled_ = 0.0;   // 1 - exp(-lambda_enabled * step)
  double decay_disabled_ = 0.0;  // 1 - exp(-lambda_disabled * step)

  TimePoint now_;
  double w_ = 0.0;      // motor rad/s
  double theta_ = 0.0;  // motor rad, 0 at start
  std::int64_t count_ = 0;
  double voltage_ = 0.0;
  bool enabled_ = false;
  bool stuck_ = true;  // w == 0 and friction/stop holds it
  int stop_ = 0;       // -1 at min stop, +1 at max stop
};

}  // namespace armctl::joint_sim
