#include "devices/joint_sim/joint_hardware.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace armctl::joint_sim {

namespace {

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

int sign_of(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

}  // namespace

JointHardware::JointHardware(const JointHardwareParams& params, TimePoint start)
    : p_(params),
      inertia_(params.total_inertia_kgm2()),
      clicks_per_rad_(params.clicks_per_motor_rev() / (2.0 * std::numbers::pi)),
      step_s_(seconds(params.step)),
      now_(start) {
  if (p_.end_stops) {
    stop_min_rad_ = p_.end_stops->min_clicks / clicks_per_rad_;
    stop_max_rad_ = p_.end_stops->max_clicks / clicks_per_rad_;
  }
  const MotorParams& m = p_.motor;
  const double k = m.torque_constant_nm_per_a;
  decay_enabled_ = -std::expm1(-(k * k / m.resistance_ohm + m.viscous_friction_nms) / inertia_ *
                               step_s_);
  decay_disabled_ = -std::expm1(-m.viscous_friction_nms / inertia_ * step_s_);
  update_stuck();
}

void JointHardware::set_drive(std::int16_t duty, bool enable) {
  set_drive_fraction(double(duty) / double(p_.pwm_max), enable);
}

void JointHardware::set_drive_fraction(double duty, bool enable) {
  duty = std::clamp(duty, -1.0, 1.0);
  voltage_ = (p_.leads_swapped ? -duty : duty) * p_.motor.supply_v;
  enabled_ = enable;
  update_stuck();
}

double JointHardware::current_a() const {
  if (!enabled_) return 0.0;
  return (voltage_ - p_.motor.torque_constant_nm_per_a * w_) / p_.motor.resistance_ohm;
}

// Counting up, the levels AB go 00 -> 01 -> 11 -> 10 (B leads A), the convention of the
// portable QuadratureDecoder.
bool JointHardware::encoder_a() const {
  const std::int64_t q = ((count_ % 4) + 4) % 4;
  return q == 2 || q == 3;
}

bool JointHardware::encoder_b() const {
  const std::int64_t q = ((count_ % 4) + 4) % 4;
  return q == 1 || q == 2;
}

void JointHardware::set_motor_velocity(double w_rad_s) {
  w_ = w_rad_s;
  update_stuck();
}

double JointHardware::drive_torque_at_rest() const {
  if (!enabled_) return 0.0;
  return p_.motor.torque_constant_nm_per_a * voltage_ / p_.motor.resistance_ohm;
}

void JointHardware::update_stuck() {
  if (w_ != 0.0) {
    stuck_ = false;
    return;
  }
  const double t = drive_torque_at_rest();
  stuck_ = std::abs(t) <= p_.motor.coulomb_friction_nm || (stop_ > 0 && t > 0.0) ||
           (stop_ < 0 && t < 0.0);
}

JointHardware::Coefficients JointHardware::coefficients(int direction) const {
  const MotorParams& m = p_.motor;
  const double friction = m.coulomb_friction_nm * direction;
  if (enabled_) {
    const double k = m.torque_constant_nm_per_a;
    return {(k * k / m.resistance_ohm + m.viscous_friction_nms) / inertia_,
            (k * voltage_ / m.resistance_ohm - friction) / inertia_};
  }
  return {m.viscous_friction_nms / inertia_, -friction / inertia_};
}

// Exact solution of dw/dt = alpha - lambda*w over dt.
void JointHardware::integrate(double dt, Coefficients c, double* w, double* theta) const {
  const double w0 = *w;
  if (c.lambda * dt < 1e-12) {
    *w = w0 + c.alpha * dt;
    *theta += w0 * dt + 0.5 * c.alpha * dt * dt;
    return;
  }
  const double ws = c.alpha / c.lambda;
  const double one_minus_e = dt == step_s_ ? step_decay(enabled_) : -std::expm1(-c.lambda * dt);
  *w = ws + (w0 - ws) * (1.0 - one_minus_e);
  *theta += ws * dt + (w0 - ws) * one_minus_e / c.lambda;
}

void JointHardware::advance_to(TimePoint t, EncoderEdgeSink* sink) {
  while (now_ < t) {
    if (stuck_) {
      now_ = t;
      return;
    }
    const Duration h = std::min<Duration>(t - now_, p_.step);
    const double dt = h == p_.step ? step_s_ : seconds(h);
    int direction = sign_of(w_);
    if (direction == 0) direction = sign_of(drive_torque_at_rest());
    const Coefficients c = coefficients(direction);

    double w1 = w_;
    double theta1 = theta_;
    integrate(dt, c, &w1, &theta1);

    Duration taken = h;
    if (w1 * direction <= 0.0 && w_ != 0.0) {
      // The velocity reaches zero inside this step: stop there, friction changes sign.
      double tz;
      if (c.lambda * dt < 1e-12) {
        tz = c.alpha != 0.0 ? -w_ / c.alpha : dt;
      } else {
        const double ws = c.alpha / c.lambda;
        const double ratio = ws != 0.0 ? (ws - w_) / ws : 0.0;
        tz = ratio > 1.0 ? std::log(ratio) / c.lambda : dt;
      }
      tz = std::clamp(tz, 0.0, dt);
      taken = std::clamp(Duration(std::llround(tz * 1e9)), Duration::zero(), h);
      w1 = w_;
      theta1 = theta_;
      integrate(tz, c, &w1, &theta1);
      w1 = 0.0;
    }

    int hit_stop = 0;
    if (p_.end_stops) {
      if (theta1 > stop_max_rad_) {
        theta1 = stop_max_rad_;
        hit_stop = 1;
      } else if (theta1 < stop_min_rad_) {
        theta1 = stop_min_rad_;
        hit_stop = -1;
      }
    }

    const TimePoint t0 = now_;
    now_ += taken;
    emit_edges(theta_, theta1, t0, now_, sink);
    theta_ = theta1;
    w_ = w1;
    if (hit_stop != 0) {
      w_ = 0.0;  // inelastic contact
      stop_ = hit_stop;
    } else if (stop_ != 0 && theta_ > stop_min_rad_ && theta_ < stop_max_rad_) {
      stop_ = 0;
    }
    if (w_ == 0.0) update_stuck();
  }
}

void JointHardware::emit_edges(double theta0, double theta1, TimePoint t0, TimePoint t1,
                               EncoderEdgeSink* sink) {
  const double c0 = theta0 * clicks_per_rad_;
  const double c1 = theta1 * clicks_per_rad_;
  if (c1 == c0) return;
  const double span_ns = double((t1 - t0).count());
  auto edge_time = [&](double boundary) {
    const double f = std::clamp((boundary - c0) / (c1 - c0), 0.0, 1.0);
    return t0 + Duration(std::llround(f * span_ns));
  };
  if (c1 > c0) {
    while (double(count_ + 1) <= c1) {
      ++count_;
      if (sink) sink->on_encoder_edge(encoder_a(), encoder_b(), edge_time(double(count_)));
    }
  } else {
    while (c1 < double(count_)) {
      const double boundary = double(count_);
      --count_;
      if (sink) sink->on_encoder_edge(encoder_a(), encoder_b(), edge_time(boundary));
    }
  }
}

void JointHardware::turn_by_hand(double clicks, EncoderEdgeSink* sink) {
  const double theta1 = theta_ + clicks / clicks_per_rad_;
  emit_edges(theta_, theta1, now_, now_, sink);
  theta_ = theta1;
  w_ = 0.0;
  update_stuck();
}

void JointHardware::set_end_stops(EndStops stops) {
  p_.end_stops = stops;
  stop_min_rad_ = stops.min_clicks / clicks_per_rad_;
  stop_max_rad_ = stops.max_clicks / clicks_per_rad_;
  // A joint resting against the old stop is free again once the new ones leave it room (an
  // obstacle taken away: ContactStop).
  if (stop_ != 0 && theta_ > stop_min_rad_ && theta_ < stop_max_rad_) stop_ = 0;
  if (w_ == 0.0) update_stuck();
}

}  // namespace armctl::joint_sim
