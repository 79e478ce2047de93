// The guided calibration over HTTP (docs/http-api.md "Calibration") on the embedded xArm with
// an arm file of the test's own: control needed, one session per client, each step the
// engine's, nothing written until confirm (cancel writes nothing), confirm writes the file
// with the previous one kept; bodies refused naming the field.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "api_server.hpp"
#include "calibration/joint_pictures.hpp"
#include "motion/urdf_chain.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "refusal.hpp"
#include "web/calibration_request.hpp"

namespace armctl::web::testing {
namespace {

namespace fs = std::filesystem;

fs::path arm_copy() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / ("armctl-web-cal-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* f : {"xarm.arm.json", "xarm.urdf"})
    fs::copy_file(fs::path(ARMCTL_SOURCE_DIR) / "config" / f, dir / f);
  return dir / "xarm.arm.json";
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kCal = "/api/v1/calibration/";

TEST(WebCalibration, StepsNeedControlAndAStartedSession) {
  const fs::path file = arm_copy();
  ApiServer api(file.string());
  EXPECT_EQ(api.post(kCal + "start", json::object(), "page").status, 409);  // no control
  api.take("page");
  EXPECT_EQ(api.post(kCal + "nudge", {{"joint", "servo3"}}, "page").status, 409);  // not started
  ASSERT_EQ(api.post(kCal + "start", json::object(), "page").status, 200);
  // Another client that takes control has no session of its own until it starts one.
  api.take("other");
  EXPECT_EQ(api.post(kCal + "nudge", {{"joint", "servo3"}}, "other").status, 409);
  EXPECT_EQ(api.get("/api/v1/calibration", "other").body["active"], false);
}

// Whether every servo of the emulated board has its torque `on`.
bool every_torque(xarm::EmulatorRunner& board, bool on) {
  bool all = true;
  board.with_servos([&](xarm::XarmServos& servos) {
    for (auto id : servos.servos()) all = all && servos.torque(id) == on;
  });
  return all;
}

TEST(WebCalibration, ASessionWhoseClientLosesControlEndsWithTheTorqueBackOn) {
  // The board on a pty, so that the test sees its servos' torque.
  xarm::EmulatorRunner board(xarm::EmulatorRunnerOptions{});
  board.start();
  ServerOptions options;
  options.control_idle = 2s;  // a client without an event stream, as this test is
  const fs::path file = arm_copy();
  ApiServer api(file.string(), options, "serial:" + board.device_path());
  api.first_positions();
  const auto released = [&] {
    ASSERT_EQ(api.post(kCal + "start", json::object(), "page").status, 200);
    const Reply r = api.post(kCal + "release", json::object(), "page");
    ASSERT_EQ(r.status, 200) << r.text;
    ASSERT_TRUE(every_torque(board, false));
  };
  const auto held_again = [&] { return api.wait_until([&](const session::ArmSnapshot&) { return every_torque(board, true); }, 20s); };

  // Taken over while the joints hang limp: the session ends, the torque back on.
  api.take("page");
  released();
  api.take("other");
  ASSERT_TRUE(held_again());
  api.take("page");
  EXPECT_EQ(api.get("/api/v1/calibration", "page").body["active"], false);

  // Gone: the page stops asking (closed, its network lost); its control ends after
  // control_idle, and the session with it.
  released();
  ASSERT_TRUE(held_again());
  EXPECT_EQ(api.get("/api/v1/state", "other").body["control"]["holder"], false);
  api.take("page");
  EXPECT_EQ(api.get("/api/v1/calibration", "page").body["active"], false);
}

TEST(WebCalibration, ThePicturesAreTheArmFilesOwn) {
  ApiServer api("scara");
  const Reply r = api.get("/api/v1/calibration/pictures");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.content_type, "image/svg+xml");
  EXPECT_EQ(r.text, calibration::joint_pictures_svg(api.worker().model()).value());
  EXPECT_NE(r.text.find("SHOULDER"), std::string::npos);  // a panel per joint, named
}

TEST(WebCalibration, BodiesAreRefusedNamingTheField) {
  const auto& m = xarm();
  auto [status, message] = refusal([&] { parse_calibration_request(m, "nudge", {{"joint", "elbow"}}); });
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("joint"), std::string::npos) << message;
  EXPECT_NE(message.find("servo3"), std::string::npos) << message;  // what is allowed
  std::tie(status, message) = refusal([&] { parse_calibration_request(m, "direction", {{"joint", 1}}); });
  EXPECT_NE(message.find("went_as_shown"), std::string::npos) << message;
  std::tie(status, message) = refusal([&] { parse_calibration_request(m, "zero", {{"joint", 1}, {"mark", "x"}}); });
  EXPECT_NE(message.find("mark"), std::string::npos) << message;
  std::tie(status, message) = refusal([&] { parse_calibration_request(m, "touch", {{"name", "a"}, {"position", {1, 2}}}); });
  EXPECT_NE(message.find("position"), std::string::npos) << message;
  std::tie(status, message) = refusal([&] { parse_calibration_request(m, "wiggle", {{"joint", 1}, {"extra", 1}}); });
  EXPECT_NE(message.find("extra"), std::string::npos) << message;
  std::tie(status, message) = refusal([&] { parse_calibration_request(m, "dance", json::object()); });
  EXPECT_NE(message.find("dance"), std::string::npos) << message;
  EXPECT_EQ(parse_calibration_request(m, "which", {{"joint", "servo2"}, {"moved", 3}}).moved, 3);
}

TEST(WebCalibration, CancelWritesNothingAndConfirmWritesTheFileThatTheServerThenDrivesWith) {
  const fs::path file = arm_copy();
  const std::string original = text_of(file);
  ApiServer api(file.string());
  api.first_positions();
  api.take("page");
  Reply r = api.post(kCal + "start", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["file"], file.string());
  EXPECT_TRUE(r.body["marks"].contains("servo3"));

  r = api.post(kCal + "find", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["find"]["devices"].size(), api.worker().model().joints.size());
  EXPECT_TRUE(r.body["find"]["silent"].empty()) << r.body["find"]["text"];
  r = api.post(kCal + "wiggle", {{"joint", "servo3"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  r = api.post(kCal + "which", {{"joint", "servo3"}, {"moved", "servo4"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["same"], false);
  EXPECT_NE(r.body["advice"].get<std::string>().find("servo4"), std::string::npos);
  r = api.post(kCal + "nudge", {{"joint", "servo3"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  r = api.post(kCal + "direction", {{"joint", "servo3"}, {"went_as_shown", false}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_EQ(r.body["changes"]["joints"].size(), 1u);
  EXPECT_EQ(r.body["changes"]["joints"][0]["flip"], true);
  EXPECT_NE(r.body["describe"].get<std::string>().find("servo3"), std::string::npos);

  r = api.post(kCal + "cancel", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(text_of(file), original);
  EXPECT_FALSE(fs::exists(file.string() + ".prev"));
  EXPECT_EQ(api.get("/api/v1/calibration", "page").body["active"], false);

  // Zeros into the arm file (ConfirmWritesAServosOffset... has the default, the servo's own).
  ASSERT_EQ(api.post(kCal + "start", {{"servo_offsets", false}}, "page").status, 200);
  ASSERT_EQ(api.post(kCal + "direction", {{"joint", "servo3"}, {"went_as_shown", false}}, "page").status, 200);
  // servo4 stands where it reads 5 deg when true (its mark): its zero moves, by 5 deg
  // (the API's units) since the arm stands at its zeros.
  const double before = api.worker().snapshot().positions[std::size_t(*api.worker().model().find_joint("servo4"))];
  r = api.post(kCal + "zero", {{"joint", "servo4"}, {"mark", 5}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["zero"]["kind"], "file_zero");
  EXPECT_NEAR(r.body["zero"]["shift"].get<double>(), 5 - before * 180 / M_PI, 0.5);
  EXPECT_EQ(r.body["changes"]["joints"].size(), 2u);
  r = api.post(kCal + "confirm", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["written"]["file"], file.string());
  const fs::path previous = r.body["written"]["previous"].get<std::string>();
  EXPECT_EQ(text_of(previous), original);
  EXPECT_NE(text_of(file), original);
  const auto written = arm::load_arm_model(file).value();
  const auto shipped = arm::load_arm_model(previous).value();
  const auto i = std::size_t(*shipped.find_joint("servo3"));
  const auto* was = shipped.joints[i].map(arm::Protocol::robot_commands);
  const auto* now = written.joints[i].map(arm::Protocol::robot_commands);
  ASSERT_TRUE(was && now);
  EXPECT_LT(was->device_per_unit() * now->device_per_unit(), 0);  // servo3 turned the other way
  EXPECT_EQ(api.get("/api/v1/calibration", "page").body["active"], false);
  // The server drives with the new file at once: a second calibration starts from it, and
  // servo4, where it stands, reads its mark.
  r = api.post(kCal + "start", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  r = api.post(kCal + "read", {{"joint", "servo4"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_NEAR(r.body["value"].get<double>(), 5, 0.5);
  ASSERT_EQ(api.post(kCal + "cancel", json::object(), "page").status, 200);
}

// The default zero step on the xArm: the servo's own offset. Confirmed, the board's servo holds
// it (saved), its shaft turned by it, and the server reads the joint in the commanded frame
// (the read-back less the offset): where it was commanded, 0, now truly at its zero.
TEST(WebCalibration, ConfirmWritesAServosOffsetThatTheServerThenReadsThrough) {
  xarm::EmulatorRunner board(xarm::EmulatorRunnerOptions{});
  board.start();
  const fs::path file = arm_copy();
  ApiServer api(file.string(), {}, "serial:" + board.device_path());
  api.first_positions();
  api.take("page");
  const std::size_t servo4 = std::size_t(*api.worker().model().find_joint("servo4"));
  const double per_deg = api.worker().model().joints[servo4].map(arm::Protocol::robot_commands)->device_per_unit() * M_PI / 180;
  ASSERT_EQ(api.post(kCal + "start", json::object(), "page").status, 200);
  Reply r = api.post(kCal + "zero", {{"joint", "servo4"}, {"mark", 5}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["zero"]["kind"], "servo_offset");
  const int units = r.body["zero"]["servo_offset"].get<int>();
  EXPECT_NEAR(units, -5 * per_deg, 1.0);
  ASSERT_EQ(r.body["changes"]["servo_offsets"].size(), 1u);
  EXPECT_NE(r.body["describe"].get<std::string>().find("turns by"), std::string::npos) << r.body["describe"];
  double shaft_before = 0;
  board.with_servos([&](xarm::XarmServos& s) { shaft_before = s.true_position(4); });
  r = api.post(kCal + "confirm", json::object(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  const arm::ArmModel written = arm::load_arm_model(file).value();
  const arm::ArmModel shipped = arm::load_arm_model(fs::path(ARMCTL_SOURCE_DIR) / "config" / "xarm.arm.json").value();
  EXPECT_EQ(written.joints[servo4].map(arm::Protocol::robot_commands)->device_a,
            shipped.joints[servo4].map(arm::Protocol::robot_commands)->device_a)
      << "the zero is in the servo, not the file";
  board.with_servos([&](xarm::XarmServos& s) {
    EXPECT_EQ(s.offset(4), units);
    EXPECT_EQ(s.saved_offset(4), units);
    EXPECT_NEAR(s.true_position(4), shaft_before + units, 1.0);
  });
  // Read through the offset: where it was commanded (0), not off by it.
  ASSERT_EQ(api.post(kCal + "start", json::object(), "page").status, 200);
  r = api.post(kCal + "read", {{"joint", "servo4"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_NEAR(r.body["value"].get<double>(), 0, 0.5);
  ASSERT_EQ(api.post(kCal + "cancel", json::object(), "page").status, 200);
}

// The 3D view draws the arm the server drives with: calibrated link lengths are in the URDF
// the page gets, not only in the kinematics.
TEST(WebCalibration, TheUrdfServedHasTheArmFilesLinkLengths) {
  const fs::path file = arm_copy();
  json doc = json::parse(text_of(file));
  doc["link_lengths"] = {{"servo4", "100mm"}};  // the shipped URDF's 97.65 mm
  std::ofstream(file) << doc.dump(2);
  ApiServer api(file.string());
  const Reply u = api.get("/api/v1/urdf");
  ASSERT_EQ(u.status, 200);
  auto chain = motion::read_urdf_chain(u.text, "base_link", api.worker().model().tool_link);
  ASSERT_TRUE(chain) << chain.error().message;
  EXPECT_EQ(chain->joints[2].name, "servo4");
  EXPECT_NEAR(chain->joints[2].origin_xyz.norm(), 0.100, 1e-12);
  EXPECT_NE(u.text, text_of(file.parent_path() / "xarm.urdf"));
}

}  // namespace
}  // namespace armctl::web::testing
