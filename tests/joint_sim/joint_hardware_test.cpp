// Physics sanity of the simulated joint hardware (motor, gearbox, encoder, H-bridge, stops).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "devices/joint_sim/joint_hardware.hpp"
#include "portable/quadrature_decoder.hpp"

namespace armctl::joint_sim {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TimePoint at(Duration d) { return TimePoint{} + d; }

JointHardwareParams frictionless() {
  JointHardwareParams p;
  p.motor.viscous_friction_nms = 0.0;
  p.motor.coulomb_friction_nm = 0.0;
  p.load_inertia_kgm2 = 0.01;
  return p;
}

struct EdgeLog final : EncoderEdgeSink {
  struct Edge {
    bool a, b;
    TimePoint t;
  };
  std::vector<Edge> edges;
  void on_encoder_edge(bool a, bool b, TimePoint t) override { edges.push_back({a, b, t}); }
};

TEST(JointHardware, NoLoadSpeedIsSupplyOverBackEmfConstant) {
  const JointHardwareParams p = frictionless();
  JointHardware hw(p);
  hw.set_drive(p.pwm_max, true);
  hw.advance_to(at(seconds(10)), nullptr);  // many mechanical time constants
  const double expected = p.motor.supply_v / p.motor.torque_constant_nm_per_a;
  EXPECT_NEAR(hw.motor_velocity_rad_s(), expected, expected * 1e-6);
  EXPECT_NEAR(hw.current_a(), 0.0, 1e-4);
}

TEST(JointHardware, NoLoadSpeedWithFrictionMatchesTorqueBalance) {
  JointHardwareParams p;  // default friction
  JointHardware hw(p);
  hw.set_drive(p.pwm_max, true);
  hw.advance_to(at(seconds(20)), nullptr);
  const MotorParams& m = p.motor;
  const double k = m.torque_constant_nm_per_a;
  const double expected = (k * m.supply_v / m.resistance_ohm - m.coulomb_friction_nm) /
                          (k * k / m.resistance_ohm + m.viscous_friction_nms);
  EXPECT_NEAR(hw.motor_velocity_rad_s(), expected, expected * 1e-6);
  EXPECT_LT(hw.motor_velocity_rad_s(), m.supply_v / k);
}

TEST(JointHardware, HalfDutyGivesHalfTheNoLoadSpeed) {
  const JointHardwareParams p = frictionless();
  JointHardware hw(p);
  hw.set_drive_fraction(-0.5, true);
  hw.advance_to(at(seconds(10)), nullptr);
  EXPECT_NEAR(hw.motor_velocity_rad_s(), -0.5 * p.motor.supply_v / p.motor.torque_constant_nm_per_a,
              1e-3);
}

TEST(JointHardware, StallCurrentIsSupplyOverResistance) {
  JointHardwareParams p;
  p.end_stops = EndStops{-10, 10};
  JointHardware hw(p);
  hw.set_drive(p.pwm_max, true);
  EXPECT_DOUBLE_EQ(hw.current_a(), p.motor.supply_v / p.motor.resistance_ohm);  // at rest
  hw.advance_to(at(seconds(1)), nullptr);  // now pushed against the stop
  EXPECT_TRUE(hw.at_end_stop());
  EXPECT_EQ(hw.motor_velocity_rad_s(), 0.0);
  EXPECT_DOUBLE_EQ(hw.current_a(), p.motor.supply_v / p.motor.resistance_ohm);
}

TEST(JointHardware, CoulombFrictionHoldsAgainstASmallDrive) {
  JointHardwareParams p;
  JointHardware hw(p);
  // Drive torque k*V/R just below the Coulomb friction.
  const MotorParams& m = p.motor;
  const double duty = 0.99 * m.coulomb_friction_nm * m.resistance_ohm /
                      (m.torque_constant_nm_per_a * m.supply_v);
  hw.set_drive_fraction(duty, true);
  EdgeLog log;
  hw.advance_to(at(seconds(5)), &log);
  EXPECT_EQ(hw.motor_velocity_rad_s(), 0.0);
  EXPECT_TRUE(log.edges.empty());
  // Just above it the joint breaks away.
  hw.set_drive_fraction(duty * 1.03, true);
  hw.advance_to(at(seconds(6)), &log);
  EXPECT_GT(hw.motor_velocity_rad_s(), 0.0);
  EXPECT_FALSE(log.edges.empty());
}

TEST(JointHardware, DisabledBridgeCoastsAndFrictionStopsIt) {
  JointHardwareParams p;
  JointHardware coast(p);
  JointHardware brake(p);
  coast.set_motor_velocity(200.0);
  brake.set_motor_velocity(200.0);
  coast.set_drive(0, false);  // H-bridge off: terminals open, no current
  brake.set_drive(0, true);   // enabled at duty 0: motor shorted, dynamic braking
  EXPECT_EQ(coast.current_a(), 0.0);
  EXPECT_LT(brake.current_a(), 0.0);
  coast.advance_to(at(milliseconds(20)), nullptr);
  brake.advance_to(at(milliseconds(20)), nullptr);
  EXPECT_GT(coast.motor_velocity_rad_s(), brake.motor_velocity_rad_s());
  // Coasting follows J dw/dt = -b w - Tc exactly: compare with the closed form.
  const double J = p.total_inertia_kgm2();
  const double b = p.motor.viscous_friction_nms;
  const double tc = p.motor.coulomb_friction_nm;
  const double ws = -tc / b;
  const double w20 = ws + (200.0 - ws) * std::exp(-b / J * 0.020);
  EXPECT_NEAR(coast.motor_velocity_rad_s(), w20, 1e-9 * 200.0);
  // Friction brings it to rest and keeps it there (no creeping back).
  coast.advance_to(at(seconds(60)), nullptr);
  EXPECT_EQ(coast.motor_velocity_rad_s(), 0.0);
  const double rest = coast.motor_angle_rad();
  coast.advance_to(at(seconds(61)), nullptr);
  EXPECT_EQ(coast.motor_angle_rad(), rest);
}

TEST(JointHardware, EndStopsClampAndRelease) {
  JointHardwareParams p;
  p.end_stops = EndStops{-500, 1000};
  JointHardware hw(p);
  hw.set_drive(200, true);
  hw.advance_to(at(seconds(1)), nullptr);
  EXPECT_TRUE(hw.at_end_stop());
  EXPECT_DOUBLE_EQ(hw.position_clicks(), 1000.0);
  EXPECT_EQ(hw.encoder_count(), 1000);
  hw.set_drive(-200, true);
  hw.advance_to(at(seconds(2)), nullptr);
  EXPECT_TRUE(hw.at_end_stop());
  EXPECT_DOUBLE_EQ(hw.position_clicks(), -500.0);
  EXPECT_EQ(hw.encoder_count(), -500);
  hw.set_drive(100, true);
  hw.advance_to(at(seconds(2) + milliseconds(5)), nullptr);
  EXPECT_FALSE(hw.at_end_stop());
  EXPECT_GT(hw.position_clicks(), -500.0);
}

TEST(JointHardware, EncoderGivesFourClicksPerLineInQuadratureOrder) {
  JointHardwareParams p;
  JointHardware hw(p);
  EdgeLog log;
  hw.set_drive(120, true);
  hw.advance_to(at(milliseconds(300)), &log);
  hw.set_drive(-255, true);
  hw.advance_to(at(milliseconds(900)), &log);
  ASSERT_GT(log.edges.size(), 1000u);
  // Decoded by the portable decoder the firmware uses: same count, no invalid transitions.
  joint_bus::QuadratureDecoder decoder;
  decoder.reset(false, false);
  bool last_a = false, last_b = false;
  TimePoint last_t{};
  for (const auto& e : log.edges) {
    EXPECT_NE((e.a != last_a) + (e.b != last_b), 2) << "two channels changed at once";
    EXPECT_GE(e.t, last_t) << "edges out of order";
    decoder.on_edge(e.a, e.b);
    last_a = e.a;
    last_b = e.b;
    last_t = e.t;
  }
  EXPECT_EQ(decoder.errors(), 0);
  EXPECT_EQ(decoder.count(), hw.encoder_count());
  EXPECT_EQ(hw.encoder_count(), std::llround(std::floor(hw.position_clicks())));
  // Clicks per motor revolution = 4 x lines.
  EXPECT_NEAR(hw.position_clicks() / (hw.motor_angle_rad() / (2 * M_PI)),
              4.0 * p.encoder_lines_per_rev, 1e-6);
}

TEST(JointHardware, ExactIntegrationDoesNotDependOnTheStep) {
  JointHardwareParams coarse;
  coarse.step = std::chrono::microseconds(1000);
  JointHardwareParams fine = coarse;
  fine.step = std::chrono::microseconds(5);
  JointHardware a(coarse), b(fine);
  for (int ms = 0; ms < 400; ++ms) {
    const auto duty = static_cast<std::int16_t>(255.0 * std::sin(ms / 40.0));
    a.set_drive(duty, ms < 300);
    b.set_drive(duty, ms < 300);
    a.advance_to(at(milliseconds(ms + 1)), nullptr);
    b.advance_to(at(milliseconds(ms + 1)), nullptr);
  }
  EXPECT_NEAR(a.position_clicks(), b.position_clicks(), 1e-6 * std::abs(b.position_clicks()) + 1e-6);
  EXPECT_NEAR(a.motor_velocity_rad_s(), b.motor_velocity_rad_s(), 1e-6);
}

TEST(JointHardware, GearboxRatioIs2448Over121) {
  JointHardwareParams p;
  EXPECT_DOUBLE_EQ(p.gear_ratio(), 2448.0 / 121.0);
  EXPECT_DOUBLE_EQ(p.total_inertia_kgm2(),
                   p.motor.rotor_inertia_kgm2 + p.load_inertia_kgm2 / (p.gear_ratio() * p.gear_ratio()));
}

}  // namespace
}  // namespace armctl::joint_sim
