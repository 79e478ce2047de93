// Frames as the API carries them <-> group actions (web/group_frames.hpp), base64 for .rob
// files, the control lease, and where a program's error is placed.
#include "web/group_frames.hpp"

#include <gtest/gtest.h>

#include "core/source_place.hpp"
#include "devices/robot_commands/group_start.hpp"
#include "files/rob_file.hpp"
#include "session/arm_worker.hpp"
#include "web/api_error.hpp"
#include "refusal.hpp"
#include "web/base64.hpp"
#include "web/control_lease.hpp"
#include "web/program_check.hpp"
#include "web/static_assets.hpp"

namespace armctl::web {
namespace {

using json = nlohmann::json;

json frame(int time_ms, double value) {
  json positions = json::object();
  for (const auto& j : xarm().joints) positions[j.name] = j.role == arm::JointRole::gripper ? 0.0 : value;
  return {{"time_ms", time_ms}, {"positions", positions}};
}

TEST(GroupFrames, RoundTripThroughServoUnits) {
  const json frames = json::array({frame(1000, 0.0), frame(500, 20.0)});
  const GroupFrames g = frames_to_group(xarm(), frames);
  ASSERT_EQ(g.group.actions.size(), 2u);
  EXPECT_EQ(g.group.actions[0].time_ms, 1000);
  EXPECT_EQ(g.group.actions[0].targets.size(), xarm().joints.size());
  const json back = group_to_frames(xarm(), g.group);
  ASSERT_EQ(back.size(), 2u);
  for (const auto& j : xarm().joints) {
    if (j.role == arm::JointRole::gripper) continue;
    // A servo unit is 0.24 deg: the value comes back to within half of one.
    EXPECT_NEAR(back[1]["positions"][j.name].get<double>(), 20.0, 0.13) << j.name;
  }
}

TEST(GroupFrames, EveryFrameIsCheckedBeforeAnythingIsReturned) {
  json frames = json::array({frame(1000, 0.0), frame(40000, 0.0)});
  auto [status, message] = refusal([&] { frames_to_group(xarm(), frames); });
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("frames[1].time_ms: 40000 is not allowed; a whole number 0..30000"), std::string::npos)
      << message;
  frames = json::array({frame(1000, 0.0), frame(1000, 500.0)});
  EXPECT_NE(refusal([&] { frames_to_group(xarm(), frames); }).second.find("outside the servo's 0..1000"),
            std::string::npos);
  json other = frame(1000, 0.0);
  other["positions"].erase(xarm().joints[0].name);
  frames = json::array({frame(1000, 0.0), other});
  EXPECT_NE(refusal([&] { frames_to_group(xarm(), frames); }).second.find("same joints"), std::string::npos);
  EXPECT_EQ(refusal([&] { frames_to_group(xarm(), json::array()); }).first, 400);
  EXPECT_NE(refusal([&] { frames_to_group(xarm(), json::array({{{"time_ms", 1}, {"positions", {{"nope", 1}}}}})); })
                .second.find("frames[0].positions.nope: arm xarm has no such joint"),
            std::string::npos);
}

TEST(GroupFrames, GroupNumbersRunsAndSpeeds) {
  EXPECT_EQ(parse_group_number("0"), 0);
  EXPECT_EQ(parse_group_number("254"), 254);
  EXPECT_EQ(refusal([] { parse_group_number("255"); }).first, 400);
  EXPECT_EQ(refusal([] { parse_group_number("speedy"); }).first, 400);
  EXPECT_EQ(parse_group_run({{"count", 3}}), 3);
  EXPECT_EQ(parse_group_run({{"continuous", true}}), 0);
  EXPECT_EQ(refusal([] { parse_group_run({{"count", 3}, {"continuous", true}}); }).first, 400);
  EXPECT_EQ(refusal([] { parse_group_run({{"count", 0}}); }).first, 400);
  EXPECT_EQ(parse_group_speed({{"percent", 150}}), 150);
  EXPECT_NE(refusal([] { parse_group_speed({{"percent", 0}}); }).second.find("percent: 0 is not allowed; a whole "
                                                                             "number 1..1000"),
            std::string::npos);
}

TEST(GroupFrames, ImportAndExportOfGroupAndRobFiles) {
  const json frames = json::array({frame(1000, 0.0), frame(500, 20.0)});
  const json text = export_group(xarm(), {{"format", "group"}, {"frames", frames}});
  const auto from_text = parse_group_import({{"format", "group"}, {"content", text["content"]}});
  EXPECT_EQ(from_text, frames_to_group(xarm(), frames).group);
  const json rob = export_group(xarm(), {{"format", "rob"}, {"frames", frames}});
  const auto bytes = base64_decode(rob["content"].get<std::string>());
  ASSERT_TRUE(bytes);
  EXPECT_EQ(bytes->size(), files::kRobHeaderBytes + 2 * files::kRobFrameBytes);
  const auto from_rob = parse_group_import({{"format", "rob"}, {"content", rob["content"]}});
  EXPECT_EQ(group_to_frames(xarm(), from_rob), group_to_frames(xarm(), from_text));
  EXPECT_NE(refusal([] { parse_group_import({{"format", "rob"}, {"content", "***"}}); }).second.find("not base64"),
            std::string::npos);
  EXPECT_EQ(refusal([] { parse_group_import({{"format", "group"}, {"content", "1000 1=2000"}}); }).first, 400);
}

TEST(Base64, RoundTripsAndRefusesBadText) {
  for (std::size_t n = 0; n < 8; ++n) {
    std::vector<std::uint8_t> bytes;
    for (std::size_t i = 0; i < n; ++i) bytes.push_back(std::uint8_t(i * 77 + 3));
    EXPECT_EQ(base64_decode(base64_encode(bytes)), bytes) << n;
  }
  EXPECT_EQ(base64_encode({'M', 'a'}), "TWE=");
  EXPECT_FALSE(base64_decode("TWE"));
  EXPECT_FALSE(base64_decode("TW=E"));
  EXPECT_FALSE(base64_decode("TWE=TWE="));
}

TEST(ControlLease, OneHolderAtATime) {
  ControlLease lease;
  EXPECT_NE(refusal([&] { lease.require("a"); }).second.find("no client has control"), std::string::npos);
  lease.take("a");
  EXPECT_TRUE(lease.view("a").you);
  EXPECT_FALSE(lease.view("b").you);
  EXPECT_TRUE(lease.view("b").holder);
  lease.take("b");
  EXPECT_FALSE(lease.view("a").you);
  auto [status, message] = refusal([&] { lease.require("a"); });
  EXPECT_EQ(status, 409);
  EXPECT_NE(message.find("another client has control (since 20"), std::string::npos) << message;
  lease.release("a");  // not the holder: nothing changes
  EXPECT_TRUE(lease.view("b").you);
  lease.release("b");
  EXPECT_FALSE(lease.view("b").holder);
  EXPECT_EQ(refusal([&] { lease.take(""); }).first, 400);
  EXPECT_EQ(check_client_id("page-1a2b", true), "page-1a2b");
  EXPECT_EQ(check_client_id("", false), "");
  EXPECT_EQ(refusal([] { check_client_id("a b", true); }).first, 400);
}

TEST(ControlLease, EndsWhenItsPageGoesAwayOrAfterIdleTime) {
  auto now = std::chrono::steady_clock::time_point{};
  ControlLease lease(std::chrono::seconds(60), std::chrono::seconds(5), [&] { return now; });
  // A page: its stream open, control taken; quiet for longer than the idle time, it keeps it.
  lease.stream_opened("page");
  lease.take("page");
  now += std::chrono::minutes(10);
  EXPECT_TRUE(lease.view("page").you);
  // Reloaded: a second stream opens before the first closes; closing the first keeps it.
  lease.stream_opened("page");
  lease.stream_closed("page");
  EXPECT_TRUE(lease.view("other").holder);
  // Its stream dropped and came back within the grace time: still its.
  lease.stream_closed("page");
  now += std::chrono::seconds(3);
  EXPECT_TRUE(lease.view("page").you);
  lease.stream_opened("page");
  now += std::chrono::seconds(30);
  EXPECT_TRUE(lease.view("page").you);
  // Closed: its last stream ends, and control with it once the grace time has passed.
  lease.stream_closed("page");
  now += std::chrono::seconds(4);
  EXPECT_TRUE(lease.view("other").holder);
  now += std::chrono::seconds(1);
  EXPECT_FALSE(lease.view("other").holder);
  // A script without a stream keeps control while it sends requests, and loses it 60 s after
  // its last one.
  lease.take("script");
  now += std::chrono::seconds(50);
  lease.seen("script");
  now += std::chrono::seconds(50);
  EXPECT_TRUE(lease.view("script").you);
  now += std::chrono::seconds(11);
  EXPECT_FALSE(lease.view("other").holder);
  EXPECT_EQ(refusal([&] { lease.require("script"); }).first, 409);
  // Another client's stream closing changes nothing.
  lease.take("script");
  lease.stream_opened("watcher");
  lease.stream_closed("watcher");
  EXPECT_TRUE(lease.view("script").you);
}

// 409 or 500 follows the error's typed detail, whatever its message says.
TEST(ApiStatus, RefusalsAreTheirDetailsNotTheirWords) {
  using session::JobRefused;
  const std::string words = "busy: stopped before it started; group 1 did not start";
  EXPECT_EQ(status_of(Error{ErrorKind::device, words}), 500);
  EXPECT_EQ(status_of(Error{ErrorKind::device, "x", JobRefused{JobRefused::Reason::busy, "move", "program"}}), 409);
  EXPECT_EQ(status_of(Error{ErrorKind::device, "x", JobRefused{JobRefused::Reason::dropped, "move", ""}}), 409);
  EXPECT_EQ(status_of(Error{ErrorKind::device, "x", JobRefused{JobRefused::Reason::closing, "move", ""}}), 500);
  EXPECT_EQ(status_of(Error{ErrorKind::device, "x", robot_commands::GroupNotStarted{3, {}}}), 409);
  EXPECT_EQ(status_of(Error{ErrorKind::timeout, "x", robot_commands::GroupNotStarted{3, {}}}), 409);
  EXPECT_EQ(status_of(Error{ErrorKind::invalid_argument, words}), 400);
  EXPECT_EQ(status_of(Error{ErrorKind::unsupported, "x"}), 409);
  // The router's refusal keeps the error, detail and all.
  try {
    fail(Error{ErrorKind::device, "x", JobRefused{JobRefused::Reason::busy, "move", "program"}});
    FAIL() << "fail() returned";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), 409);
    ASSERT_NE(e.error(), nullptr);
    ASSERT_NE(session::job_refusal(*e.error()), nullptr);
    EXPECT_EQ(session::job_refusal(*e.error())->running, "program");
  }
}

TEST(ProgramCheck, ErrorsArePlacedAtTheirLine) {
  // Placed by the error's SourcePlace, never by its text: a message that looks like a place
  // is not one, and a place is found whatever the message says.
  const PlacedError e = place_error(source_error(ErrorKind::invalid_config, {"program", 12, 5, "found 'x', expected a move"}));
  EXPECT_EQ(e.file, "program");
  EXPECT_EQ(e.line, 12u);
  EXPECT_EQ(e.column, 5u);
  EXPECT_EQ(e.message, "found 'x', expected a move");
  const PlacedError l = place_error(source_error(ErrorKind::invalid_argument, {"program", 3, 0, "(LIN pick): no IK solution"}));
  EXPECT_EQ(l.line, 3u);
  EXPECT_EQ(l.column, 0u);
  EXPECT_EQ(l.message, "(LIN pick): no IK solution");
  const PlacedError other = place_error(Error{ErrorKind::invalid_config, "anything", SourcePlace{"points", 2, 1, "found '1'"}});
  EXPECT_EQ(other.file, "points");
  EXPECT_EQ(other.line, 2u);
  EXPECT_EQ(other.message, "found '1'");
  const PlacedError text_only = place_error(Error{ErrorKind::invalid_config, "program:12:5: found 'x'"});
  EXPECT_EQ(text_only.line, 0u);
  EXPECT_EQ(text_only.message, "program:12:5: found 'x'");
  ProgramRequest unknown_point;
  unknown_point.source = "wait 1s\nptp home\n";
  CheckedProgram c = check_program(unknown_point, nullptr, {});
  ASSERT_EQ(c.errors.size(), 1u);
  EXPECT_EQ(c.errors[0].line, 2u) << c.errors[0].message;  // no points file: 'home' is no point
  EXPECT_EQ(c.errors[0].column, 5u) << c.errors[0].message;
  ProgramRequest bad_points;
  bad_points.source = "ptp home\n";
  bad_points.points = "home joints=0deg\n9bad x=1mm\n";
  c = check_program(bad_points, nullptr, {});
  ASSERT_EQ(c.errors.size(), 1u);
  EXPECT_EQ(c.errors[0].file, "points");
  EXPECT_EQ(c.errors[0].line, 2u) << c.errors[0].message;
  ProgramRequest good = bad_points;
  good.points = "home joints=0deg\n";
  EXPECT_TRUE(check_program(good, nullptr, {}).errors.empty());
}

TEST(StaticAssets, TheIndexIsEmbeddedWithItsType) {
  const StaticAsset* index = find_asset("/");
  ASSERT_NE(index, nullptr);
  EXPECT_STREQ(index->path, "/index.html");
  EXPECT_NE(index->data().find("<html"), std::string_view::npos);
  EXPECT_EQ(find_asset("/nope.js"), nullptr);
  EXPECT_STREQ(content_type_for("/a/b.js"), "text/javascript; charset=utf-8");
  EXPECT_STREQ(content_type_for("/x.CSS"), "text/css; charset=utf-8");
  EXPECT_STREQ(content_type_for("/x.png"), "image/png");
  EXPECT_STREQ(content_type_for("/dir.v2/file"), "application/octet-stream");
}

}  // namespace
}  // namespace armctl::web
