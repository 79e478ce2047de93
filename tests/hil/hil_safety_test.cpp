// Safe in the field, on both arms ("sim": the portable code; "avr": the firmware ELF on
// emulated ATmega328P chips), through the bus master: the default polarity matches the
// original boards' wiring, the reversed setting matches swapped motor leads, a wrong one is
// a runaway that the joint stops by itself and reports; read_diagnostic / clear_faults; and
// legacy-master mode under a simulated original Mega master (COMMAND handed to the UART,
// select lowered 30 us later, STATUS awaited for 50 ms), for every command.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <tuple>
#include <vector>

#include "arm_backends.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "portable/fault_monitor.hpp"
#include "portable/joint_bus_codes.hpp"

namespace armctl::hil {
namespace {

using joint_bus::BusMaster;
using std::chrono::milliseconds;

using Param = std::tuple<std::string, std::uint32_t>;  // backend, baud

class HilSafety : public ::testing::TestWithParam<Param> {
 protected:
  std::unique_ptr<ArmBackend> make(Scenario s = {}) {
    s.baud = std::get<1>(GetParam());
    auto b = make_backend(std::get<0>(GetParam()), s);
    b->advance(milliseconds(20));
    return b;
  }
};

// Joint 3 (UAE) moves 1500 clicks; true if it got there without a fault.
void expect_settles(ArmBackend& arm, BusMaster& m, int joint) {
  ASSERT_TRUE(m.drive_to(joint, 1500).ok());
  arm.advance(milliseconds(1500));
  EXPECT_NEAR(arm.hardware(joint).position_clicks(), 1500, 8);
  const auto d = m.read_diagnostics(joint);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d.value().faults, 0);
}

TEST_P(HilSafety, DefaultPolaritySettlesOnTheOriginalWiring) {
  auto arm = make();
  BusMaster m(arm->link());
  expect_settles(*arm, m, 3);
  EXPECT_FALSE(m.read_diagnostics(3).value().motor_reversed());
}

TEST_P(HilSafety, ReversedPolaritySettlesOnSwappedLeads) {
  Scenario s;
  s.options.polarity = joint_bus::MotorPolarity::reversed;
  s.leads_swapped = {1, 2, 3, 4, 5, 6, 7};
  auto arm = make(s);
  BusMaster m(arm->link());
  expect_settles(*arm, m, 3);
  EXPECT_TRUE(m.read_diagnostics(3).value().motor_reversed());
}

TEST_P(HilSafety, WrongPolarityRunsAwayIsStoppedAndReportedUntilCleared) {
  Scenario s;
  s.leads_swapped = {3};  // a board wired for the other polarity
  auto arm = make(s);
  BusMaster m(arm->link());
  ASSERT_TRUE(m.drive_to(3, 1500).ok());
  arm->advance(milliseconds(600));
  const auto d = m.read_diagnostics(3);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_TRUE(d.value().runaway());
  const double stopped_at = arm->hardware(3).position_clicks();
  EXPECT_LT(stopped_at, -64) << "it ran the wrong way";
  // Braked to rest, then the bridge is off; drives are refused.
  arm->advance(milliseconds(1000));
  EXPECT_TRUE(arm->hardware(3).resting());
  EXPECT_GT(arm->hardware(3).position_clicks(), -6000) << "stopped long before the end stop (-32000)";
  std::printf("runaway: %.0f clicks at 600 ms, at rest at %.0f\n", stopped_at, arm->hardware(3).position_clicks());
  const auto refused = m.drive_to(3, 0);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(joint_bus::joint_failure(refused.error())->kind, joint_bus::FailureKind::bad_data);
  if (auto* avr = dynamic_cast<AvrBackend*>(arm.get())) {
    EXPECT_FALSE(avr->arm().joint(3).chip().bridge_inputs().enable);
  }
  // Other joints are unaffected.
  EXPECT_EQ(m.read_diagnostics(2).value().faults, 0);
  // Cleared: it holds where it is (no jump), then runs away again on the next move.
  ASSERT_TRUE(m.clear_faults(3).ok());
  EXPECT_EQ(m.read_diagnostics(3).value().faults, 0);
  const std::int16_t here = m.get_position(3).value();
  EXPECT_EQ(m.get_target(3).value(), here);
  arm->advance(milliseconds(300));
  EXPECT_LE(std::abs(m.get_position(3).value() - here), 3);
}

TEST_P(HilSafety, DiagnosticsReportResetCauseAndSettings) {
  Scenario s;
  s.options.legacy_master = false;
  auto arm = make(s);
  BusMaster m(arm->link());
  const auto d = m.read_diagnostics(5);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d.value().reset_cause & 1u, 1u) << "power-on reset";
  EXPECT_EQ(d.value().uart_errors, 0);
  EXPECT_EQ(d.value().bus_events_lost, 0);
  EXPECT_EQ(d.value().encoder_edges_lost, 0);
  EXPECT_FALSE(d.value().legacy_master());
  const auto bad = m.read_diagnostic(5, joint_bus::diagnostic_count);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(joint_bus::joint_failure(bad.error())->code(), 940);
}

// The original Mega master, on the simulated bus.
struct LegacyAnswer {
  std::vector<std::uint8_t> ready;
  std::vector<std::uint8_t> after;
};

LegacyAnswer legacy_transact(transport::JointBusLink& link, int joint, std::int16_t command,
                             std::optional<std::int16_t> data) {
  using joint_bus::word_high;
  using joint_bus::word_low;
  LegacyAnswer a;
  link.drain();
  link.set_select(joint, true);
  const TimePoint ready_deadline = link.clock().now() + milliseconds(50);
  while (a.ready.size() < 2) {
    auto b = link.read_byte(ready_deadline);
    if (!b) break;
    a.ready.push_back(*b);
  }
  std::vector<std::uint8_t> out{word_low(command), word_high(command)};
  if (data) {
    out.push_back(word_low(*data));
    out.push_back(word_high(*data));
  }
  link.write(out);  // handed to the UART; no flush
  const TimePoint lower_at = link.clock().now() + std::chrono::microseconds(30);
  while (auto b = link.read_byte(lower_at)) a.after.push_back(*b);
  link.set_select(joint, false);
  const bool returns_value = joint_bus::command_shape(command).returns_value;
  const std::size_t expected = returns_value ? 4 : 2;
  const TimePoint give_up = link.clock().now() + milliseconds(50);
  while (a.after.size() < expected) {
    auto b = link.read_byte(give_up);
    if (!b) break;
    a.after.push_back(*b);
  }
  return a;
}

std::vector<std::uint8_t> words(std::initializer_list<std::int16_t> ws) {
  std::vector<std::uint8_t> b;
  for (std::int16_t w : ws) {
    b.push_back(joint_bus::word_low(w));
    b.push_back(joint_bus::word_high(w));
  }
  return b;
}

TEST_P(HilSafety, LegacyMasterModeAnswersTheOriginalMasterForEveryCommand) {
  using namespace joint_bus;
  Scenario s;
  s.options.legacy_master = true;
  auto arm = make(s);
  auto& link = arm->link();
  const int j = 4;
  const auto run = [&](std::int16_t c, std::optional<std::int16_t> d = std::nullopt) {
    return legacy_transact(link, j, c, d);
  };
  EXPECT_EQ(run(cmd_ping, 4321).ready, words({4}));
  EXPECT_EQ(run(cmd_ping, 4321).after, words({4321, cmd_ping}));
  EXPECT_EQ(run(cmd_get_joint_number).after, words({4, cmd_get_joint_number}));
  EXPECT_EQ(run(cmd_set_speed, 255).after, words({cmd_set_speed}));
  EXPECT_EQ(run(cmd_set_zone, 5).after, words({cmd_set_zone}));
  EXPECT_EQ(run(cmd_drive_to, 800).after, words({cmd_drive_to}));
  EXPECT_EQ(run(cmd_get_target).after, words({800, cmd_get_target}));
  EXPECT_EQ(run(cmd_drive_dist, -200).after, words({cmd_drive_dist}));
  EXPECT_EQ(run(cmd_get_target).after, words({600, cmd_get_target}));
  arm->advance(milliseconds(1500));
  EXPECT_EQ(run(cmd_check_target_reached).after, words({1, cmd_check_target_reached}));
  const auto pos = run(cmd_get_position).after;
  ASSERT_EQ(pos.size(), 4u);
  const std::int16_t p = word_from(pos[0], pos[1]);
  EXPECT_LE(std::abs(p - 600), 5);
  EXPECT_EQ(std::vector<std::uint8_t>(pos.begin() + 2, pos.end()), words({cmd_get_position}));
  EXPECT_EQ(run(cmd_drive_dist_max, 100).after, words({cmd_drive_dist_max}));
  EXPECT_EQ(run(cmd_set_speed, 128).after, words({cmd_set_speed}));  // half the speed
  EXPECT_EQ(run(cmd_set_pid_state, 0).after, words({cmd_set_pid_state}));
  EXPECT_EQ(run(cmd_set_pid_state, 1).after, words({cmd_set_pid_state}));
  EXPECT_EQ(run(cmd_home).after, words({cmd_home}));
  EXPECT_EQ(run(cmd_get_target).after, words({0, cmd_get_target}));
  EXPECT_EQ(run(cmd_read_diagnostic, diagnostic_settings).after,
            words({setting_legacy_master, cmd_read_diagnostic}));
  EXPECT_EQ(run(cmd_clear_faults).after, words({cmd_clear_faults}));
  EXPECT_EQ(run(cmd_set_speed, 256).after, words({legacy_status_bad_data}));
  EXPECT_EQ(run(cmd_set_pid_state, 2).after, words({legacy_status_bad_data}));
  EXPECT_EQ(run(3).after, words({legacy_status_unknown_command}));
  EXPECT_EQ(run(cmd_ping, 99).after, words({99, cmd_ping}));
  // Our own master in the legacy dialect talks to the same joints.
  MasterOptions o;
  o.dialect = Dialect::legacy;
  BusMaster m(link, o);
  EXPECT_EQ(m.ping(j, 7).value(), 7);
  EXPECT_TRUE(m.set_speed(j, 200).ok());
  const auto unknown = m.transact(j, 93, std::nullopt);
  ASSERT_FALSE(unknown.ok()) << "93 answered with 93 is unknown, not success";
  EXPECT_EQ(joint_bus::joint_failure(unknown.error())->kind, FailureKind::unknown_command);
  EXPECT_TRUE(m.read_diagnostics(j).value().legacy_master());
}

TEST_P(HilSafety, AStandardJointIgnoresTheOriginalMastersTiming) {
  auto arm = make();
  const auto a = legacy_transact(arm->link(), 4, joint_bus::cmd_drive_to, 800);
  EXPECT_TRUE(a.after.empty());
  BusMaster m(arm->link());
  EXPECT_EQ(m.get_target(4).value(), 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, HilSafety,
                         ::testing::Combine(::testing::Values("sim", "avr"), ::testing::Values(9600u, 115200u)),
                         [](const ::testing::TestParamInfo<Param>& p) {
                           return std::get<0>(p.param) + "_" + std::to_string(std::get<1>(p.param));
                         });

}  // namespace
}  // namespace armctl::hil
