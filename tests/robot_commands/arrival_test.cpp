// wait_until_arrived on simulated time against the emulated xArm: it waits for the servos
// (not for the move's time), names the ones that did not arrive with target and position,
// skips "leave alone" entries, and returns the client's error when positions cannot be read.
#include <gtest/gtest.h>

#include "devices/robot_commands/arrival.hpp"
#include "sim_links.hpp"

namespace armctl::robot_commands {
namespace {

using namespace std::chrono_literals;
using testing::EmulatedLink;
using testing::ScriptedLink;

TEST(WaitUntilArrived, WaitsForTheServosNotForTheMoveTime) {
  EmulatedLink link;
  Client c(link);
  const std::vector<ServoTarget> targets{{1, 0}, {2, 1000}, {3, std::nullopt}};
  // 0 ms asks for "as fast as it can": the emulated servos need 500 units / 1500 units/s.
  ASSERT_TRUE(c.move(targets, 0));
  const TimePoint start = c.clock().now();
  auto r = wait_until_arrived(c, targets, start + 2s, ArrivalOptions{.tolerance = 0});
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->all_arrived());
  ASSERT_EQ(r->servos.size(), 3u);
  EXPECT_EQ(r->servos[0], (ServoArrival{1, 0, 0, true}));
  EXPECT_EQ(r->servos[1], (ServoArrival{2, 1000, 1000, true}));
  EXPECT_EQ(r->servos[2], (ServoArrival{3, std::nullopt, 500, true}));  // left alone
  // Arrival is seen within one poll period of the servos' real travel time.
  EXPECT_GE(r->elapsed, 333ms);
  EXPECT_LE(r->elapsed, 333ms + 25ms);
  EXPECT_EQ(r->elapsed, c.clock().now() - start);
}

TEST(WaitUntilArrived, NamesEveryServoThatIsNotThereAtTheDeadline) {
  EmulatedLink link;
  Client c(link);
  const std::vector<ServoTarget> targets{{1, 0}, {2, 1000}, {4, 500}};
  ASSERT_TRUE(c.move(targets, 0));
  const TimePoint start = c.clock().now();
  auto r = wait_until_arrived(c, targets, start + 100ms);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_FALSE(r->all_arrived());
  const auto missed = r->missed();
  ASSERT_EQ(missed.size(), 2u);
  EXPECT_EQ(missed[0].servo, 1);
  EXPECT_EQ(missed[0].target, 0);
  EXPECT_EQ(missed[1].servo, 2);
  // 100 ms at 1500 units/s: about 150 units on the way from 500.
  EXPECT_NEAR(missed[0].position, 350, 15);
  EXPECT_NEAR(missed[1].position, 650, 15);
  EXPECT_TRUE(r->servos[2].arrived);  // servo 4 was already at 500
  EXPECT_GE(c.clock().now() - start, 100ms);
  EXPECT_LE(c.clock().now() - start, 100ms + 1ms);
}

TEST(WaitUntilArrived, AServoGlidingThroughTheBandHasNotArrived) {
  EmulatedLink link;
  Client c(link);
  // 200 units over 1 s: 4 units per 20 ms poll, inside 10 units of the target 50 ms early.
  const std::vector<ServoTarget> targets{{1, 700}};
  ASSERT_TRUE(c.move(targets, 1000));
  const TimePoint start = c.clock().now();
  auto r = wait_until_arrived(c, targets, start + 2s);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->all_arrived());
  EXPECT_EQ(r->servos[0].position, 700) << "arrived only once there";
  EXPECT_GE(r->elapsed, 1s);
}

TEST(WaitUntilArrived, DeclaresNoArrivalBeforeTheMovesPlannedEnd) {
  EmulatedLink link;
  Client c(link);
  // 20 units over 1 s: reads 20 ms apart differ by at most 1, so in the band the servo
  // looks at rest long before the end.
  const std::vector<ServoTarget> targets{{1, 520}};
  ASSERT_TRUE(c.move(targets, 1000));
  const TimePoint start = c.clock().now();
  auto early = wait_until_arrived(c, targets, start + 2s);
  ASSERT_TRUE(early) << early.error().message;
  EXPECT_LT(early->elapsed, 1s);
  EXPECT_LT(early->servos[0].position, 520);

  ASSERT_TRUE(c.move({{1, 500}}, 1000));
  const TimePoint again = c.clock().now();
  auto r = wait_until_arrived(c, {{1, 500}}, again + 2s, {.not_before = again + 1s});
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->all_arrived());
  EXPECT_EQ(r->servos[0].position, 500);
  EXPECT_EQ(r->elapsed, 1s);
}

TEST(WaitUntilArrived, ReadsOnceEvenWhenTheDeadlineHasPassed) {
  EmulatedLink link;
  Client c(link);
  auto r = wait_until_arrived(c, {{5, 500}}, c.clock().now() - 1s);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->all_arrived());
  EXPECT_EQ(r->servos.at(0).position, 500);
}

TEST(WaitUntilArrived, ABoardThatDoesNotAnswerIsTheClientsTimeout) {
  ScriptedLink silent;
  Client c(silent, ClientOptions{.reply_timeout = 50ms});
  auto r = wait_until_arrived(c, {{1, 200}}, c.clock().now() + 1s);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::timeout);
  EXPECT_NE(r.error().message.find("ServoPositionRead"), std::string::npos) << r.error().message;
}

TEST(WaitUntilArrived, RefusesABadToleranceOrPeriodBeforeReading) {
  ScriptedLink link;
  Client c(link);
  EXPECT_EQ(wait_until_arrived(c, {{1, 200}}, c.clock().now(), {.tolerance = -1}).error().kind,
            ErrorKind::invalid_argument);
  EXPECT_EQ(wait_until_arrived(c, {{1, 200}}, c.clock().now(), {.tolerance = 1001}).error().kind,
            ErrorKind::invalid_argument);
  EXPECT_EQ(
      wait_until_arrived(c, {{1, 200}}, c.clock().now(), {.poll_period = Duration::zero()}).error().kind,
      ErrorKind::invalid_argument);
  EXPECT_TRUE(link.sent.empty());
}

}  // namespace
}  // namespace armctl::robot_commands
