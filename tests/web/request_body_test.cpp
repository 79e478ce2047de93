// The API's request bodies (web/request_body.hpp): every field range-checked, unknown
// fields refused, every error naming the field, the value and what is allowed.
#include "web/request_body.hpp"

#include <gtest/gtest.h>

#include "arm/arm_model.hpp"
#include "web/api_error.hpp"
#include "refusal.hpp"

namespace armctl::web {
namespace {

TEST(RequestBody, EmptyBodyIsAnEmptyObject) {
  EXPECT_EQ(parse_body(""), json::object());
  EXPECT_EQ(parse_body(" \n"), json::object());
}

TEST(RequestBody, RefusesWhatIsNotAJsonObject) {
  EXPECT_EQ(refusal([] { parse_body("{"); }).first, 400);
  auto [status, message] = refusal([] { parse_body("[1,2]"); });
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("must be a JSON object"), std::string::npos) << message;
  EXPECT_NE(refusal([] { parse_body("1e400"); }).second.find("not valid JSON"), std::string::npos);
}

TEST(RequestBody, RefusesAKeyGivenTwice) {
  // nlohmann would keep the last: {"speed": 0.1, "speed": 1} would move at full speed.
  auto [status, message] = refusal([] { parse_body(R"({"speed": 0.1, "speed": 1})"); });
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("key \"speed\" appears twice in one object"), std::string::npos) << message;
  EXPECT_EQ(refusal([] { parse_body(R"({"a": {"b": 1, "b": 2}})"); }).first, 400);
  // The same key in two objects is fine.
  EXPECT_EQ(parse_body(R"({"a": {"b": 1}, "c": {"b": 2}})")["c"]["b"], 2);
}

TEST(RequestBody, RefusesDeepNestingAndLargeBodies) {
  const std::string deep = std::string(100, '[') + std::string(100, ']');
  EXPECT_NE(refusal([&] { parse_body("{\"a\":" + deep + "}"); }).second.find("nested deeper"), std::string::npos);
  const std::string big(kMaxBodyBytes + 1, ' ');
  EXPECT_EQ(refusal([&] { parse_body(big); }).first, 413);
}

TEST(RequestBody, JointsInDisplayUnitsToSi) {
  const auto& m = xarm();
  const std::string name = m.joints[1].name;
  const auto r = parse_joints_request(m, json{{"positions", {{name, 30.0}}}, {"speed", 0.5}});
  ASSERT_EQ(r.targets.size(), m.joints.size());
  EXPECT_NEAR(*r.targets[1], 30.0 * M_PI / 180, 1e-12);
  EXPECT_FALSE(r.targets[0]);
  EXPECT_DOUBLE_EQ(r.speed, 0.5);
  EXPECT_FALSE(r.duration);
}

TEST(RequestBody, JointErrorsNameTheFieldAndWhatIsAllowed) {
  const auto& m = xarm();
  const std::string name = m.joints[0].name;
  auto msg = [&](const json& body) { return refusal([&] { parse_joints_request(m, body); }).second; };
  EXPECT_NE(msg({{"positions", {{"elbowx", 1}}}}).find("positions.elbowx: arm xarm has no such joint; joints: "),
            std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, "ten"}}}}).find("\"ten\" is not a number"), std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, 1}}}, {"speed", 0}}).find("speed: 0 is not allowed; a fraction"),
            std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, 1}}}, {"speed", 1.5}}).find("speed: 1.5 is not allowed"), std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, 1}}}, {"speed", 0.5}, {"duration", 2}}).find("not both"), std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, 1}}}, {"fast", true}}).find("fast: unknown field (allowed here: "),
            std::string::npos);
  EXPECT_NE(msg(json::object()).find("positions: missing"), std::string::npos);
  EXPECT_NE(msg({{"positions", json::object()}}).find("at least one joint"), std::string::npos);
  EXPECT_NE(msg({{"positions", {{name, 1}}}, {"duration", 601}}).find("duration: 601 is not allowed; seconds"),
            std::string::npos);
}

TEST(RequestBody, ToolAndJog) {
  const auto t = parse_tool_request({{"x", 200}, {"y", 0}, {"z", 150}, {"pitch", 90}, {"linear", true}});
  EXPECT_NEAR(t.position.x(), 0.2, 1e-12);
  EXPECT_NEAR(*t.pitch, M_PI / 2, 1e-12);
  EXPECT_FALSE(t.roll);
  EXPECT_TRUE(t.linear);
  EXPECT_NE(refusal([] { parse_tool_request({{"x", 200}, {"y", 0}}); }).second.find("z: missing"), std::string::npos);
  EXPECT_NE(refusal([] { parse_tool_request({{"x", 1e9}, {"y", 0}, {"z", 0}}); }).second.find("x: 1000000000.0 is not "
                                                                                              "allowed; mm"),
            std::string::npos);
  const auto j = parse_jog_request({{"axis", "yaw"}, {"step", -5}});
  EXPECT_EQ(j.axis, 5);
  EXPECT_NEAR(j.step, -5 * M_PI / 180, 1e-12);
  EXPECT_NE(refusal([] { parse_jog_request({{"axis", "w"}, {"step", 1}}); }).second.find("axis: \"w\" is not allowed; "
                                                                                         "one of \"x\""),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_jog_request({{"axis", "x"}, {"step", 0}}); }).second.find("step: 0 is not allowed"),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_jog_request({{"axis", "x"}, {"step", 150}}); }).second.find("-100..100"),
            std::string::npos);
}

TEST(RequestBody, ServoATwistOrOneJointsVelocity) {
  const auto& m = xarm();
  // A tool axis: the twist along it, in m/s.
  const auto t = parse_servo_request(m, {{"axis", "y"}, {"speed", -20}, {"frame", "tool"}});
  const auto& twist = std::get<arm::ToolTwist>(t.motion);
  EXPECT_DOUBLE_EQ(twist.linear.y(), -0.02);
  EXPECT_EQ(twist.frame, arm::ServoFrame::tool);
  // One joint: its velocity in rad/s, every other joint still.
  const auto j = parse_servo_request(m, {{"joint", m.joints[3].name}, {"speed", 30}});
  const auto& v = std::get<arm::JointVelocities>(j.motion).values;
  ASSERT_EQ(v.size(), m.joints.size());
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], i == 3 ? 30 * M_PI / 180 : 0.0, 1e-12) << i;
}

TEST(RequestBody, ServoErrorsNameTheFieldAndWhatIsAllowed) {
  const auto& m = xarm();
  const std::string name = m.joints[2].name;
  auto msg = [&](const json& body) { return refusal([&] { parse_servo_request(m, body); }).second; };
  EXPECT_NE(msg({{"speed", 10}}).find("axis: missing; give \"axis\" (the tool along or about x, y, z"),
            std::string::npos)
      << msg({{"speed", 10}});
  EXPECT_NE(msg({{"axis", "x"}, {"joint", name}, {"speed", 10}}).find("joint: give \"axis\""), std::string::npos);
  EXPECT_NE(msg({{"axis", "x"}, {"joint", name}, {"speed", 10}}).find(", not both"), std::string::npos);
  EXPECT_NE(msg({{"axis", "w"}, {"speed", 10}}).find("axis: \"w\" is not allowed; one of \"x\""), std::string::npos);
  EXPECT_NE(msg({{"axis", "x"}, {"speed", 101}}).find("speed: 101 is not allowed; mm/s (signed; 0 stops), -100..100"),
            std::string::npos);
  EXPECT_NE(msg({{"joint", "elbowx"}, {"speed", 10}}).find("joint: \"elbowx\": arm xarm has no such joint; joints: "),
            std::string::npos);
  EXPECT_NE(msg({{"joint", 3}, {"speed", 10}}).find("joint: 3 is not allowed; a joint's name: "), std::string::npos);
  // The joint's own velocity limit (180 deg/s on the xArm) in its unit.
  EXPECT_NE(msg({{"joint", name}, {"speed", -200}})
                .find("speed: -200 is not allowed; deg/s (signed; 0 stops), -180..180: joint " + name +
                      "'s velocity limit"),
            std::string::npos)
      << msg({{"joint", name}, {"speed", -200}});
  EXPECT_NE(msg({{"joint", name}}).find("speed: missing"), std::string::npos) << msg({{"joint", name}});
  EXPECT_NE(msg({{"joint", m.joints[std::size_t(m.gripper->joint)].name}, {"speed", 10}})
                .find("is the gripper: POST /api/v1/gripper moves it"),
            std::string::npos);
  // A frame is a tool twist's: with a joint it is an unknown field.
  EXPECT_NE(msg({{"joint", name}, {"speed", 10}, {"frame", "tool"}}).find("frame: unknown field"), std::string::npos);
}

TEST(RequestBody, SmallRequests) {
  EXPECT_DOUBLE_EQ(parse_gripper_request({{"closed", 0.25}}), 0.25);
  EXPECT_NE(refusal([] { parse_gripper_request({{"closed", 2}}); }).second.find("closed: 2 is not allowed"),
            std::string::npos);
  EXPECT_TRUE(parse_torque_request({{"on", true}}));
  EXPECT_NE(refusal([] { parse_torque_request({{"on", "yes"}}); }).second.find("true or false"), std::string::npos);
  EXPECT_TRUE(parse_control_request({{"take", true}}).take);
  EXPECT_FALSE(parse_control_request({{"release", true}}).take);
  EXPECT_EQ(refusal([] { parse_control_request({{"take", true}, {"release", true}}); }).first, 400);
  EXPECT_EQ(refusal([] { parse_control_request(json::object()); }).first, 400);
  EXPECT_EQ(parse_point_request({{"name", "pick_2"}}), "pick_2");
  EXPECT_NE(refusal([] { parse_point_request({{"name", "lin"}}); }).second.find("word of the program language"),
            std::string::npos);
  EXPECT_EQ(refusal([] { parse_point_request({{"name", "2pick"}}); }).first, 400);
  EXPECT_EQ(refusal([] { parse_empty_request({{"x", 1}}); }).first, 400);
  const auto p = parse_program_request({{"source", "PTP home"}, {"speed", 0.5}}, true);
  EXPECT_EQ(p.source, "PTP home");
  EXPECT_DOUBLE_EQ(p.speed, 0.5);
  EXPECT_EQ(refusal([] { parse_program_request({{"source", "x"}, {"speed", 0.5}}, false); }).first, 400);
}

}  // namespace
}  // namespace armctl::web
