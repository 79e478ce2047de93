// The API's moves on the embedded simulators: joints, tool, jog, gripper, torque; every bad
// input refused with the documented status and a clear message, and nothing moves; STOP
// from a client without control; one job at a time.
#include <cmath>

#include <fmt/core.h>

#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

double deg(double rad) { return rad * 180 / M_PI; }

class WebMoves : public ::testing::Test {
 protected:
  void SetUp() override {
    before_ = api_.first_positions();
    api_.take("page");
  }
  const arm::ArmModel& model() { return api_.worker().model(); }
  // The request was refused with `status`, a message containing `says`, and nothing moved.
  void refused(const std::string& path, const json& body, int status, const std::string& says) {
    const Reply r = api_.post(path, body, "page");
    EXPECT_EQ(r.status, status) << path << " " << body.dump() << " -> " << r.text;
    ASSERT_TRUE(r.body.is_object()) << r.text;
    EXPECT_NE(r.body["error"].get<std::string>().find(says), std::string::npos)
        << body.dump() << ": " << r.body["error"].get<std::string>();
    EXPECT_FALSE(api_.worker().busy());
    EXPECT_EQ(api_.worker().snapshot().device, before_.device) << body.dump();
  }
  ApiServer api_{"xarm"};
  session::ArmSnapshot before_;
};

TEST_F(WebMoves, JointsMoveTheArmThere) {
  const auto& j = model().joints[1];
  const Reply r = api_.post("/api/v1/joints", {{"positions", {{j.name, 20.0}}}, {"speed", 0.5}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["moving"], true);
  ASSERT_TRUE(api_.wait_idle());
  const auto s = api_.worker().snapshot();
  EXPECT_TRUE(s.last_error.empty()) << s.last_error;
  EXPECT_NEAR(deg(s.positions[1]), 20.0, 0.5);
  EXPECT_NEAR(s.positions[0], before_.positions[0], 0.01);  // the others stay
  // And the state says so, in deg.
  const Reply state = api_.get("/api/v1/state", "page");
  EXPECT_NEAR(state.body["joints"][1]["position"].get<double>(), 20.0, 0.5);
}

TEST_F(WebMoves, JointsWithADuration) {
  const auto& j = model().joints[0];
  const Reply r = api_.post("/api/v1/joints", {{"positions", {{j.name, -30.0}}}, {"duration", 2.0}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_NEAR(r.body["duration_s"].get<double>(), 2.0, 0.05);
  ASSERT_TRUE(api_.wait_idle());
  EXPECT_NEAR(deg(api_.worker().snapshot().positions[0]), -30.0, 0.5);
}

// A duration shorter than the arm file allows is stretched, as in every app, and the reply
// says so; 2 s (above) is long enough and has no note.
TEST_F(WebMoves, AJointsDurationTooShortIsStretchedAndSaysSo) {
  const auto& j = model().joints[0];
  const Reply r = api_.post("/api/v1/joints", {{"positions", {{j.name, 97.4}}}, {"duration", 0.1}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_GE(r.body["duration_s"].get<double>(), 97.4 / deg(j.limits.velocity)) << r.text;
  ASSERT_TRUE(r.body.contains("note")) << r.text;
  EXPECT_EQ(r.body["note"].get<std::string>().rfind(
                fmt::format("duration 0.1 s is too short for joint {} to move 97.", j.name), 0),
            0u)
      << r.text;
  ASSERT_TRUE(api_.wait_idle());
  const Reply slow = api_.post("/api/v1/joints", {{"positions", {{j.name, 90.0}}}, {"duration", 2.0}}, "page");
  ASSERT_EQ(slow.status, 200) << slow.text;
  EXPECT_FALSE(slow.body.contains("note")) << slow.text;
  ASSERT_TRUE(api_.wait_idle());
}

TEST_F(WebMoves, BadJointRequestsMoveNothing) {
  const auto& j = model().joints[0];
  const double above = deg(j.limits.upper) + 10;
  refused("/api/v1/joints", {{"positions", {{j.name, above}}}}, 400,
          fmt::format("joint {}: target", j.name));
  refused("/api/v1/joints", {{"positions", {{j.name, above}}}}, 400, "is outside its limits");
  refused("/api/v1/joints", {{"positions", {{"nosuch", 1}}}}, 400, "positions.nosuch: arm xarm has no such joint");
  refused("/api/v1/joints", {{"positions", {{j.name, "1"}}}}, 400, "is not a number");
  refused("/api/v1/joints", {{"positions", {{j.name, 1}}}, {"speed", 0}}, 400, "speed: 0 is not allowed");
  refused("/api/v1/joints", {{"positions", {{j.name, 1}}}, {"speed", -1}}, 400, "speed: -1 is not allowed");
  refused("/api/v1/joints", {{"positions", {{j.name, 1}}}, {"duration", -1}}, 400, "duration: -1 is not allowed");
  refused("/api/v1/joints", {{"positions", {{j.name, 1}}}, {"velocity", 1}}, 400, "velocity: unknown field");
  refused("/api/v1/joints", json::object(), 400, "positions: missing");
  // Two joints, one of them bad: neither moves.
  refused("/api/v1/joints", {{"positions", {{model().joints[1].name, 10}, {j.name, above}}}}, 400, "outside its limits");
  const Reply not_json = api_.send("POST", "/api/v1/joints", "{\"positions\":", "page");
  EXPECT_EQ(not_json.status, 400);
  EXPECT_NE(not_json.body["error"].get<std::string>().find("not valid JSON"), std::string::npos);
  const Reply huge = api_.send("POST", "/api/v1/joints", std::string(2 << 20, ' '), "page");
  EXPECT_EQ(huge.status, 413);
  EXPECT_NE(huge.body["error"].get<std::string>().find("1 MiB"), std::string::npos) << huge.text;
  EXPECT_EQ(api_.worker().snapshot().device, before_.device);
}

TEST_F(WebMoves, ToolPtpAndLinear) {
  const auto s = api_.worker().snapshot();
  ASSERT_TRUE(s.pose);
  const Eigen::Vector3d p = s.pose->position * 1e3;
  Reply r = api_.post("/api/v1/tool", {{"x", p.x()}, {"y", p.y()}, {"z", p.z() - 30}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api_.wait_idle());
  auto now = api_.worker().snapshot();
  EXPECT_TRUE(now.last_error.empty()) << now.last_error;
  EXPECT_NEAR(now.pose->position.z() * 1e3, p.z() - 30, 2.0);
  r = api_.post("/api/v1/tool", {{"x", p.x()}, {"y", p.y()}, {"z", p.z() - 10}, {"linear", true}, {"speed", 0.25}},
                "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api_.wait_idle());
  now = api_.worker().snapshot();
  EXPECT_TRUE(now.last_error.empty()) << now.last_error;
  EXPECT_NEAR(now.pose->position.z() * 1e3, p.z() - 10, 2.0);
}

TEST_F(WebMoves, BadToolRequestsMoveNothing) {
  refused("/api/v1/tool", {{"x", 100}, {"y", 0}}, 400, "z: missing");
  refused("/api/v1/tool", {{"x", 5000}, {"y", 0}, {"z", 0}}, 400, "x: 5000 is not allowed; mm, -2000..2000");
  refused("/api/v1/tool", {{"x", 1500}, {"y", 0}, {"z", 100}}, 400, "");  // out of reach: IK says why
  refused("/api/v1/tool", {{"x", 1500}, {"y", 0}, {"z", 100}, {"linear", true}}, 400, "");
  refused("/api/v1/tool", {{"x", 100}, {"y", 0}, {"z", 100}, {"linear", "yes"}}, 400, "linear: \"yes\" is not allowed");
}

TEST_F(WebMoves, Jog) {
  const double z = api_.worker().snapshot().pose->position.z() * 1e3;
  const Reply r = api_.post("/api/v1/jog", {{"axis", "z"}, {"step", -10}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api_.wait_idle());
  const auto now = api_.worker().snapshot();
  EXPECT_TRUE(now.last_error.empty()) << now.last_error;
  EXPECT_NEAR(now.pose->position.z() * 1e3, z - 10, 2.0);
}

TEST_F(WebMoves, BadJogsMoveNothing) {
  refused("/api/v1/jog", {{"axis", "q"}, {"step", 1}}, 400, "axis: \"q\" is not allowed");
  refused("/api/v1/jog", {{"axis", "x"}, {"step", 0}}, 400, "step: 0 is not allowed");
  refused("/api/v1/jog", {{"axis", "roll"}, {"step", 100}}, 400, "step: 100 is not allowed");
  refused("/api/v1/jog", {{"axis", "x"}}, 400, "step: missing");
}

TEST_F(WebMoves, GripperAndTorque) {
  Reply r = api_.post("/api/v1/gripper", {{"closed", 1.0}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api_.wait_idle());
  const auto& g = *model().gripper;
  EXPECT_NEAR(api_.worker().snapshot().positions[std::size_t(g.joint)], g.closed, 0.02);
  before_ = api_.worker().snapshot();
  refused("/api/v1/gripper", {{"closed", 1.5}}, 400, "closed: 1.5 is not allowed; how far closed, 0 (open) up to 1");
  before_ = api_.worker().snapshot();
  r = api_.post("/api/v1/torque", {{"on", false}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["torque"], false);
  r = api_.post("/api/v1/torque", {{"on", true}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  before_ = api_.worker().snapshot();
  refused("/api/v1/torque", {{"on", 1}}, 400, "on: 1 is not allowed; true or false");
  // Clearing joint faults: nothing held on this arm, so nothing moves and the answer is yes.
  r = api_.post("/api/v1/clear-faults", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["faults_cleared"], true);
  before_ = api_.worker().snapshot();
  refused("/api/v1/clear-faults", {{"joint", 3}}, 400, "joint");
}

TEST_F(WebMoves, StopFromAnyoneHaltsAMove) {
  const auto& j = model().joints[0];
  const double target = deg(j.limits.upper) * 0.9;
  const Reply r = api_.post("/api/v1/joints", {{"positions", {{j.name, target}}}, {"speed", 0.1}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  // Under way, then a client without control stops it.
  ASSERT_TRUE(api_.wait_until([&](const session::ArmSnapshot& s) {
    return !s.job.empty() && std::abs(s.positions[0] - before_.positions[0]) > 0.05;
  }));
  const Reply busy = api_.post("/api/v1/joints", {{"positions", {{j.name, 0}}}}, "page");
  EXPECT_EQ(busy.status, 409);
  EXPECT_NE(busy.body["error"].get<std::string>().find("busy"), std::string::npos) << busy.text;
  const Reply stop = api_.send("POST", "/api/v1/stop", "{}", "watcher");
  ASSERT_EQ(stop.status, 200) << stop.text;
  EXPECT_EQ(stop.body["stopped"], true);
  EXPECT_EQ(stop.body["link_ok"], true);
  EXPECT_FALSE(stop.body.contains("warning"));
  ASSERT_TRUE(api_.wait_idle(10s));
  // It comes to rest (two reads in a row the same) short of the target.
  std::vector<double> previous;
  ASSERT_TRUE(api_.wait_until([&](const session::ArmSnapshot& s) {
    const bool rest = s.device == previous;
    previous = s.device;
    return rest;
  }));
  EXPECT_LT(deg(api_.worker().snapshot().positions[0]), target - 5) << "the move was not stopped";
  // A stop without a body or client works too (curl -X POST).
  EXPECT_EQ(api_.send("POST", "/api/v1/stop", "").status, 200);
}

}  // namespace
}  // namespace armctl::web::testing
