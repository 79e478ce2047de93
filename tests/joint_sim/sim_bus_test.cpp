// Wire timing, select lines, contention and fault injection of the simulated joint bus.
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "bus_bytes.hpp"
#include "core/error.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/joint_sim/sim_bus.hpp"

namespace armctl::joint_sim {
namespace {

using std::chrono::milliseconds;
using testing::read_word;
using testing::succeeded;
using testing::transact;

// A scripted endpoint: records what it receives and sends what the test queues.
struct FakeEndpoint final : BusEndpoint {
  std::vector<std::pair<std::uint8_t, TimePoint>> received;
  std::deque<std::uint8_t> to_send;
  std::vector<std::uint8_t> on_select_high;  // queued when select rises
  bool driving = false;
  void advance_to(TimePoint) override {}
  void on_select(bool high, TimePoint) override {
    if (high) to_send.insert(to_send.end(), on_select_high.begin(), on_select_high.end());
  }
  void on_rx_byte(std::uint8_t b, TimePoint t) override { received.emplace_back(b, t); }
  std::optional<TxByte> next_tx_byte(TimePoint t) override {
    if (to_send.empty()) return std::nullopt;
    const std::uint8_t b = to_send.front();
    to_send.pop_front();
    return TxByte{b, t};
  }
  bool tx_enabled() const override { return driving; }
  TimePoint next_event_time() const override { return TimePoint::max(); }
};

TEST(SimBus, MasterBytesTakeTenBitTimesEach) {
  for (std::uint32_t baud : {9600u, 115200u}) {
    FakeEndpoint a, b;
    SimBus bus(baud, {&a, &b});
    const Duration bt = wire_time(1, baud);
    EXPECT_EQ(bus.byte_time(), bt);
    bus.advance(milliseconds(3));
    const TimePoint t0 = bus.now();
    const std::uint8_t bytes[3] = {0x11, 0x22, 0x33};
    bus.write(bytes);
    EXPECT_EQ(bus.now(), t0);  // writing does not move time
    bus.flush();
    EXPECT_EQ(bus.now(), t0 + 3 * bt);
    // Every joint's RX sees every byte when its stop bit ends.
    for (const FakeEndpoint* e : {&a, &b}) {
      ASSERT_EQ(e->received.size(), 3u);
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(e->received[i].first, bytes[i]);
        EXPECT_EQ(e->received[i].second, t0 + (i + 1) * bt);
      }
    }
  }
}

TEST(SimBus, JointBytesReachTheMasterAfterTenBitTimes) {
  FakeEndpoint a;
  a.on_select_high = {0x01, 0x00};
  SimBus bus(9600, {&a});
  const Duration bt = bus.byte_time();
  bus.set_select(1, true);
  const TimePoint t0 = bus.now();
  EXPECT_EQ(bus.read_byte(t0 + 10 * bt), 0x01);
  EXPECT_EQ(bus.now(), t0 + bt);
  EXPECT_EQ(bus.read_byte(t0 + 10 * bt), 0x00);
  EXPECT_EQ(bus.now(), t0 + 2 * bt);
  // Nothing more: read_byte waits exactly until the deadline.
  EXPECT_EQ(bus.read_byte(t0 + 7 * bt), std::nullopt);
  EXPECT_EQ(bus.now(), t0 + 7 * bt);
}

TEST(SimBus, AWholePingTakesItsWireTimeFloor) {
  auto arm = SimArm::from_default_config();
  const TimePoint t0 = arm->now();
  const auto r = transact(arm->link(), 3, joint_bus::cmd_ping, 1234);
  ASSERT_TRUE(succeeded(r, joint_bus::cmd_ping));
  EXPECT_EQ(*r.response, 1234);
  // READY, COMMAND, DATA, RESPONSE, STATUS = 10 bytes back to back (the simulated joint
  // answers at once): exactly the wire time. (The spec's "6 or 8 bytes" misses ping's 10.)
  EXPECT_EQ(arm->now() - t0, 10 * arm->bus().byte_time());
  const TimePoint t1 = arm->now();
  ASSERT_TRUE(succeeded(transact(arm->link(), 3, joint_bus::cmd_get_position),
                        joint_bus::cmd_get_position));
  EXPECT_EQ(arm->now() - t1, 8 * arm->bus().byte_time());
}

TEST(SimBus, ContentionIsCountedLoggedAndCorruptsTheByte) {
  FakeEndpoint a, b;
  a.on_select_high = {0xF0};
  b.on_select_high = {0x3C};
  SimBus bus(9600, {&a, &b});
  bus.set_select(1, true);
  bus.set_select(2, true);
  const auto got = bus.read_byte(bus.now() + milliseconds(10));
  ASSERT_TRUE(got);
  EXPECT_EQ(*got, 0xF0 & 0x3C);  // wired-AND of the two idle-high lines
  EXPECT_EQ(bus.read_byte(bus.now() + milliseconds(10)), std::nullopt);  // only one byte
  EXPECT_EQ(bus.stats().contentions, 1u);
  EXPECT_EQ(bus.stats().corrupted_bytes, 1u);
  ASSERT_FALSE(bus.log().empty());
  EXPECT_NE(bus.log().back().find("contention"), std::string::npos);
}

TEST(SimBus, TwoJointsEnablingTxIsContentionEvenWithoutBytes) {
  FakeEndpoint a, b;
  SimBus bus(9600, {&a, &b});
  a.driving = true;
  bus.set_select(1, true);
  EXPECT_EQ(bus.stats().contentions, 0u);
  b.driving = true;
  bus.set_select(2, true);
  EXPECT_EQ(bus.stats().contentions, 1u);
}

TEST(SimBus, SelectOfAMissingJointIsRefused) {
  FakeEndpoint a;
  SimBus bus(9600, {&a});
  EXPECT_THROW(bus.set_select(0, true), ArmctlError);
  EXPECT_THROW(bus.set_select(2, true), ArmctlError);
  EXPECT_THROW(SimBus(0, {&a}), ArmctlError);
}

TEST(SimBus, DrainDiscardsReceivedBytes) {
  FakeEndpoint a;
  a.on_select_high = {1, 2, 3};
  SimBus bus(115200, {&a});
  bus.set_select(1, true);
  bus.advance(milliseconds(1));
  EXPECT_EQ(bus.drain(), 3u);
  EXPECT_EQ(bus.read_byte(bus.now()), std::nullopt);
}

// --- faults, on the full simulated arm -------------------------------------------------

TEST(Faults, DroppedByteToTheMasterLeavesTheWordIncomplete) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 0));  // READY low byte
  arm->link().set_select(2, true);
  const auto first = arm->link().read_byte(arm->now() + milliseconds(20));
  EXPECT_EQ(first, 0x00);  // only READY's high byte arrives
  EXPECT_EQ(arm->link().read_byte(arm->now() + milliseconds(20)), std::nullopt);
  EXPECT_EQ(arm->bus().stats().dropped, 1u);
}

TEST(Faults, DroppedByteToTheJointsStallsItsTransaction) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_joints, 1));  // COMMAND high byte
  const auto r = transact(arm->link(), 1, joint_bus::cmd_home);
  EXPECT_EQ(r.ready, 1);
  EXPECT_EQ(r.status, std::nullopt);  // the joint never completed the command
  EXPECT_EQ(arm->joint(1).controller().transaction().completed_count(), 0);
  // The next transaction works again (the joint abandoned the broken one).
  EXPECT_TRUE(succeeded(transact(arm->link(), 1, joint_bus::cmd_home), joint_bus::cmd_home));
}

TEST(Faults, FlippedBitIsSeenByTheMaster) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.flip_bits(Wire::to_master, 0, 0x40));
  const auto r = transact(arm->link(), 3, joint_bus::cmd_ping, 5);
  EXPECT_EQ(r.ready, 0x43);  // READY 3 became 0x43: the transaction stops there
  EXPECT_EQ(arm->bus().stats().flipped, 1u);
}

TEST(Faults, FlippedBitToTheJointChangesTheData) {
  auto arm = SimArm::from_default_config();
  // Bytes to joints: COMMAND lo, hi, DATA lo, hi -> flip bit 0 of DATA lo.
  arm->set_fault_plan(FaultPlan{}.flip_bits(Wire::to_joints, 2, 0x01));
  const auto r = transact(arm->link(), 4, joint_bus::cmd_ping, 100);
  ASSERT_TRUE(succeeded(r, joint_bus::cmd_ping));
  EXPECT_EQ(r.response, 101);
}

TEST(Faults, DelayedByteArrivesLateByExactlyTheDelay) {
  auto arm = SimArm::from_default_config();
  const Duration bt = arm->bus().byte_time();
  arm->set_fault_plan(FaultPlan{}.delay_byte(Wire::to_master, 0, milliseconds(7)));
  arm->link().set_select(5, true);
  const TimePoint t0 = arm->now();
  EXPECT_EQ(arm->link().read_byte(t0 + milliseconds(50)), 5);
  EXPECT_EQ(arm->now(), t0 + milliseconds(7) + bt);
  EXPECT_EQ(arm->link().read_byte(t0 + milliseconds(50)), 0);
  EXPECT_EQ(arm->now(), t0 + milliseconds(7) + 2 * bt);
  EXPECT_EQ(arm->bus().stats().delayed, 1u);
}

TEST(Faults, DeadJointNeverAnswersOthersDo) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.dead_joint(6));
  const auto r = transact(arm->link(), 6, joint_bus::cmd_ping, 1);
  EXPECT_EQ(r.ready, std::nullopt);
  EXPECT_GT(arm->bus().stats().suppressed_dead, 0u);
  EXPECT_TRUE(succeeded(transact(arm->link(), 7, joint_bus::cmd_ping, 1), joint_bus::cmd_ping));
}

TEST(Faults, WrongNumberAnswersReadyWithIt) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.wrong_number(2, 5));
  EXPECT_EQ(transact(arm->link(), 2, joint_bus::cmd_ping, 1).ready, 5);
  EXPECT_EQ(transact(arm->link(), 3, joint_bus::cmd_ping, 1).ready, 3);
}

TEST(Faults, GarbageAppearsOnTheMastersRx) {
  auto arm = SimArm::from_default_config();
  arm->set_fault_plan(FaultPlan{}.garbage(arm->now() + milliseconds(4), {0xDE, 0xAD}));
  EXPECT_EQ(arm->link().read_byte(arm->now() + milliseconds(3)), std::nullopt);
  EXPECT_EQ(arm->link().read_byte(arm->now() + milliseconds(3)), 0xDE);
  EXPECT_EQ(arm->now(), TimePoint{} + milliseconds(4));
  EXPECT_EQ(arm->link().read_byte(arm->now()), 0xAD);
  EXPECT_EQ(arm->bus().stats().garbage_bytes, 2u);
}

TEST(Faults, RandomFaultsAreReproducibleFromTheSeed) {
  auto run = [](std::uint64_t seed) {
    auto arm = SimArm::from_default_config();
    RandomFaultRates rates;
    rates.drop = rates.flip = rates.delay = rates.garbage = 0.05;
    arm->set_fault_plan(FaultPlan{}.random(seed, rates));
    std::vector<int> outcome;
    for (int i = 0; i < 60; ++i) {
      const auto r = transact(arm->link(), 1 + i % 7, joint_bus::cmd_ping, std::int16_t(i));
      outcome.push_back(r.status ? *r.status : -1);
      outcome.push_back(r.ready ? *r.ready : -1);
    }
    const BusStats s = arm->bus().stats();
    outcome.push_back(int(s.dropped + s.flipped + s.delayed + s.garbage_bytes));
    return outcome;
  };
  const auto a = run(42), b = run(42), c = run(43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_GT(a.back(), 0);
}

TEST(Faults, BadPlansAreRefused) {
  EXPECT_THROW(FaultPlan{}.dead_joint(8), ArmctlError);
  EXPECT_THROW(FaultPlan{}.flip_bits(Wire::to_master, 0, 0), ArmctlError);
  EXPECT_THROW(FaultPlan{}.delay_byte(Wire::to_master, 0, Duration::zero()), ArmctlError);
  EXPECT_THROW(FaultPlan{}.garbage(TimePoint{}, {}), ArmctlError);
  RandomFaultRates bad;
  bad.drop = 1.5;
  EXPECT_THROW(FaultPlan{}.random(1, bad), ArmctlError);
}

}  // namespace
}  // namespace armctl::joint_sim
