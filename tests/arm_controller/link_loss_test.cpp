// The arm controller when its joint-bus link closes (the simulated arm behind `--bus unix:`
// restarted): ReconnectingLink reports the loss, retries with back-off, reports the
// recovery; meanwhile moves are refused as for dead joints; a running group ends; after the
// recovery nothing moves until a new command. All on the simulated bus's clock.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "controller_rig.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/reconnecting_link.hpp"

namespace armctl::arm_controller::testing {
namespace {

using joint_bus::ReconnectingLink;

using namespace std::chrono_literals;

// The simulated bus behind a connection that can close: broken, every call throws as a
// socket whose peer went away does.
class BreakableLink final : public transport::JointBusLink {
 public:
  explicit BreakableLink(transport::JointBusLink& bus) : bus_(bus) {}
  bool broken = false;
  int joint_count() const override { return bus_.joint_count(); }
  void set_select(int joint, bool high) override { check(), bus_.set_select(joint, high); }
  void write(std::span<const std::uint8_t> bytes) override { check(), bus_.write(bytes); }
  void flush() override { check(), bus_.flush(); }
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override { return check(), bus_.read_byte(deadline); }
  std::size_t drain() override { return check(), bus_.drain(); }
  const Clock& clock() const override { return bus_.clock(); }
  std::uint32_t baud() const override { return bus_.baud(); }

 private:
  void check() const {
    if (broken) throw ArmctlError(ErrorKind::io, "simulated arm closed the connection");
  }
  transport::JointBusLink& bus_;
};

struct LinkLossRig {
  LinkLossRig() {
    auto sim_config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    sim_config.baud = 115200;
    arm = std::make_unique<joint_sim::SimArm>(std::move(sim_config));
    auto open = [this]() -> std::shared_ptr<transport::JointBusLink> {
      ++opens;
      if (peer_down) throw ArmctlError(ErrorKind::io, "connect: no such file (the arm is not running)");
      current = std::make_shared<BreakableLink>(arm->link());
      return current;
    };
    link = std::make_unique<ReconnectingLink>(
        open, arm->link().clock(), [this](TimePoint t) { arm->run_until(t); },
        [this](const std::string& line) { log.push_back(line); });
    CoreDeviceOptions o;
    o.log = [this](const std::string& line) { log.push_back(line); };
    o.link_losses = [this] { return link->losses(); };
    device = std::make_unique<CoreDevice>(*link, load_controller_config(default_controller_config_path()), o,
                                          [this](const rc::Frame& f) { rc_link.deliver(f); });
    rc_link.attach(*device);
    robot_commands::ClientOptions co;
    co.servo_count = 7;
    client = std::make_unique<robot_commands::Client>(rc_link, co);
  }

  void close_link() {
    peer_down = true;
    current->broken = true;
  }
  void run_for(Duration d) { device->run_for(d); }
  int target(int joint) { return arm->joint(joint).controller().target(); }
  int clicks(int joint) { return arm->joint(joint).controller().position(); }
  std::size_t count(const std::string& needle) const {
    std::size_t n = 0;
    for (const auto& l : log) n += l.find(needle) != std::string::npos;
    return n;
  }

  std::unique_ptr<joint_sim::SimArm> arm;
  std::shared_ptr<BreakableLink> current;
  bool peer_down = false;
  int opens = 0;
  std::unique_ptr<ReconnectingLink> link;
  SimRcLink rc_link;
  std::unique_ptr<CoreDevice> device;
  std::unique_ptr<robot_commands::Client> client;
  std::vector<std::string> log;
};

// A host's link (WhileLost::refuse): the loss and every call after it carry LinkLost, and the
// master's errors on it say link_lost; an error of the joint itself does not.
TEST(LinkLoss, ARefusingLinkSaysTheDeviceIsLostByItsDetail) {
  auto sim_config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  joint_sim::SimArm arm(std::move(sim_config));
  std::shared_ptr<BreakableLink> current;
  bool peer_down = false;
  joint_bus::ReconnectOptions options;
  options.while_lost = joint_bus::ReconnectOptions::WhileLost::refuse;
  ReconnectingLink link(
      [&]() -> std::shared_ptr<transport::JointBusLink> {
        if (peer_down) throw ArmctlError(ErrorKind::io, "connect: the arm is not running");
        current = std::make_shared<BreakableLink>(arm.link());
        return current;
      },
      arm.link().clock(), [&](TimePoint t) { arm.run_until(t); }, nullptr, options);
  joint_bus::BusMaster master(link);
  auto fine = master.ping(1, 0x1234);
  ASSERT_TRUE(fine) << fine.error().message;
  auto unplugged = master.ping(9, 0x1234);  // no joint 9 answers: a joint's failure, not a loss
  ASSERT_FALSE(unplugged);
  EXPECT_FALSE(joint_bus::device_lost(unplugged.error()));
  peer_down = true;
  current->broken = true;
  try {
    link.flush();
    FAIL() << "a broken link did not throw";
  } catch (const ArmctlError& e) {
    ASSERT_TRUE(joint_bus::device_lost(e.error())) << e.what();
    EXPECT_EQ(e.error().detail_as<joint_bus::LinkLost>()->why, "simulated arm closed the connection");
  }
  auto lost = master.ping(1, 0x1234);
  ASSERT_FALSE(lost);
  EXPECT_TRUE(joint_bus::device_lost(lost.error())) << lost.error().message;
  ASSERT_NE(joint_bus::joint_failure(lost.error()), nullptr);
  EXPECT_TRUE(joint_bus::joint_failure(lost.error())->link_lost);
}

TEST(LinkLoss, ReconnectsWithBackOffAndReportsEachAttemptAndTheRecovery) {
  LinkLossRig rig;
  rig.run_for(200ms);
  rig.close_link();
  rig.run_for(6s);
  EXPECT_EQ(rig.link->losses(), 1u);
  EXPECT_FALSE(rig.link->connected());
  EXPECT_EQ(rig.count("joint bus link lost: simulated arm closed the connection"), 1u);
  // 0.1 s, then doubling to at most 2 s: attempts at 0.1, 0.3, 0.7, 1.5, 3.1, 5.1 s.
  EXPECT_EQ(rig.link->attempts(), 6u);
  for (const char* next : {"next in 0.2 s", "next in 0.4 s", "next in 0.8 s", "next in 1.6 s"})
    EXPECT_EQ(rig.count(next), 1u) << next;
  EXPECT_EQ(rig.count("next in 2.0 s"), 2u);  // the cap
  EXPECT_EQ(rig.count("next in 3.2 s"), 0u);
  EXPECT_EQ(rig.count("reconnect attempt 6 failed: connect: no such file"), 1u);

  rig.peer_down = false;
  rig.run_for(2500ms);
  EXPECT_TRUE(rig.link->connected());
  EXPECT_EQ(rig.link->recoveries(), 1u);
  EXPECT_EQ(rig.count("joint bus link back after 7 attempts"), 1u);
  for (int j = 1; j <= 7; ++j) EXPECT_TRUE(rig.device->joint_state(j).answering) << "joint " << j;
  // And it works again.
  ASSERT_TRUE(rig.client->move({{1, 600}}, 500).ok());
  rig.run_for(1500ms);
  EXPECT_EQ(rig.target(1), rig.device->config().joint(1)->map.to_clicks(600));
}

TEST(LinkLoss, WhileDisconnectedMovesAreRefusedAsForDeadJoints) {
  LinkLossRig rig;
  rig.run_for(200ms);
  const int before = rig.target(2);
  rig.close_link();
  rig.run_for(500ms);  // every joint's poll has failed by now
  ASSERT_TRUE(rig.client->move({{2, 700}}, 500).ok());  // no reply in Robot Commands: sent
  rig.run_for(500ms);
  EXPECT_GE(rig.count("MultiServoMove refused: joint 2 (SHOULDER) is not answering"), 1u);
  EXPECT_EQ(rig.device->core().stats().refused_moves, 1u);
  // Positions are still answered (the last good readings), like for a dead joint.
  auto positions = rig.client->read_positions({1, 2});
  ASSERT_TRUE(positions.ok()) << positions.error().message;
  rig.peer_down = false;
  rig.run_for(3s);
  ASSERT_TRUE(rig.link->connected());
  EXPECT_EQ(rig.target(2), before) << "the refused move was carried out after the recovery";
}

TEST(LinkLoss, AGroupRunningAtTheLossEndsAndNothingMovesAfterTheRecovery) {
  LinkLossRig rig;
  std::vector<robot_commands::GroupAction> actions;
  for (std::uint16_t p : {400, 600, 400, 600, 400, 600, 400, 600})
    actions.push_back({1000, {{1, p}, {2, p}}});
  ASSERT_TRUE(rig.client->download_group(3, actions).ok());
  ASSERT_TRUE(rig.client->run_group(3, 1).ok());
  rig.run_for(1500ms);  // the second action is under way
  rig.close_link();
  rig.run_for(1s);
  EXPECT_EQ(rig.count("joint bus link lost: playback and queued commands ended"), 1u);
  EXPECT_FALSE(rig.device->core().playing());
  // The host is told the run ended: CMD 7 with no DATA, as after a GroupStop (a host that
  // sent no stop reads it as "finished", as the spec asks of hosts).
  bool ended = false;
  (void)rig.client->pump_events(rig.device->clock().now());
  while (auto e = rig.client->next_event())
    ended = ended || e->kind == rc::GroupEventKind::stopped || e->kind == rc::GroupEventKind::finished;
  EXPECT_TRUE(ended);

  rig.peer_down = false;
  rig.run_for(3s);
  ASSERT_TRUE(rig.link->connected());
  const int target1 = rig.target(1), target2 = rig.target(2);
  const int at1 = rig.clicks(1), at2 = rig.clicks(2);
  const auto commands = rig.device->core().stats().commands;
  rig.run_for(8s);  // the rest of the group would have played by now
  EXPECT_EQ(rig.target(1), target1);
  EXPECT_EQ(rig.target(2), target2);
  EXPECT_NEAR(rig.clicks(1), at1, 20);
  EXPECT_NEAR(rig.clicks(2), at2, 20);
  EXPECT_EQ(rig.device->core().stats().commands, commands) << "commands sent after the recovery with none asked";
}

}  // namespace
}  // namespace armctl::arm_controller::testing
