// Teach driven from a script on both simulated arms (simulated clock): torque off, hand
// moves through the simulators' test hooks, points recorded and read back; a continuous
// recording replayed through the motion layer and compared with what was recorded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <functional>

#include "arm/arm.hpp"
#include "arm/arm_files.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"
#include "teach/replay.hpp"
#include "teach/teach.hpp"

namespace armctl::teach {
namespace {

using arm::testing::shipped;

// A script of lines, each with a hand move done just before it is "typed".
struct Script {
  std::deque<std::pair<std::function<void()>, std::string>> lines;
  std::vector<std::string> said;
  std::vector<TeachEvent> events;
  TeachIo io() {
    return {[this]() -> std::optional<std::string> {
              if (lines.empty()) return std::nullopt;
              auto [move, text] = lines.front();
              lines.pop_front();
              if (move) move();
              return text;
            },
            [this](const TeachEvent& e) {
              said.push_back(e.text);
              events.push_back(e);
            }};
  }
};

std::string temp_file(const std::string& name) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::remove(path.c_str());
  return path;
}

// The largest joint distance (SI) from each recorded sample to the nearest point of the
// replayed motion (sampled every ms): how closely the replay follows the recording's path.
double path_deviation(const motion::Recording& r, const arm::PlannedMotion& m, std::size_t joints) {
  std::vector<std::vector<double>> path;
  std::vector<double> p(joints), v(joints), a(joints);
  for (double t = 0; t <= m.duration + 1e-9; t += 0.001) {
    m.sample(t, p, v, a);
    path.push_back(p);
  }
  double worst = 0;
  for (const auto& s : r.samples) {
    double best = 1e9;
    for (const auto& q : path) {
      double d = 0;
      for (std::size_t j = 0; j < joints; ++j) d = std::max(d, std::abs(q[j] - s.positions[j]));
      best = std::min(best, d);
    }
    worst = std::max(worst, best);
  }
  return worst;
}

class XarmTeach : public ::testing::Test {
 public:
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  arm::Arm arm{shipped("xarm"), std::make_unique<arm::RcArmDevice>(shipped("xarm"), client)};
  xarm::XarmServos& servos() { return link.emulator().servos(); }
  // Where the hand puts servo `id`, as the Arm reads it (SI).
  bool hand(int joint, double si) {
    const auto& map = *arm.model().joints[std::size_t(joint)].map(arm::Protocol::robot_commands);
    return servos().move_by_hand(std::uint8_t(map.id), std::round(map.to_device(si)));
  }
  std::vector<double> here() { return arm.read().value().positions; }
};

TEST_F(XarmTeach, PointsFromAScriptTorqueOffThenOnHolding) {
  const std::string path = temp_file("xarm.points");
  EXPECT_FALSE(hand(0, 0.3));  // torque on: a hand cannot move the servo
  Script script;
  script.lines.push_back({[&] { EXPECT_TRUE(hand(0, 0.3)); }, ""});
  script.lines.push_back({[&] { EXPECT_TRUE(hand(1, -0.4)); }, "  pick "});
  script.lines.push_back({nullptr, "lin"});
  script.lines.push_back({[&] { EXPECT_TRUE(hand(2, 0.5)); }, "pick"});
  script.lines.push_back({nullptr, ""});
  auto n = teach_points(arm, path, script.io());
  ASSERT_TRUE(n) << n.error().message;
  EXPECT_EQ(*n, 4u);  // p1, pick, pick again, p2 ('lin' refused)
  for (int id = 1; id <= 6; ++id) EXPECT_TRUE(servos().torque(std::uint8_t(id)));
  EXPECT_FALSE(hand(2, 0.0));
  const std::vector<double> held = here();
  link.sim_clock().advance(std::chrono::seconds(2));
  EXPECT_EQ(here(), held);  // holding where it stands
  EXPECT_NEAR(held[2], 0.5, 0.005);

  auto file = files::read_points_file(path);
  ASSERT_TRUE(file) << file.error().message;
  ASSERT_EQ(file->points.size(), 3u);
  EXPECT_EQ(file->points[0].name, "p1");
  EXPECT_EQ(file->points[1].name, "pick");
  EXPECT_EQ(file->points[2].name, "p2");
  EXPECT_NEAR(file->points[0].joints[0].value, 0.3, 0.005);
  EXPECT_NEAR(file->points[1].joints[1].value, -0.4, 0.005);
  EXPECT_NEAR(file->points[1].joints[2].value, 0.5, 0.005);  // replaced: taken at the later place
  ASSERT_EQ(file->points[2].joints.size(), std::size_t(arm.model().joint_count()));
  for (std::size_t j = 0; j < held.size(); ++j) EXPECT_NEAR(file->points[2].joints[j].value, held[j], 1e-9);
  // The same as values (what `teach --json` prints): each event's kind, point and joints.
  std::vector<std::string> kinds;
  for (const auto& e : script.events) kinds.push_back(std::string(to_string(e.kind)) + " " + e.name);
  EXPECT_EQ(kinds, (std::vector<std::string>{"started ", "recorded p1", "recorded pick", "refused lin",
                                             "replaced pick", "recorded p2", "finished "}));
  EXPECT_NEAR(script.events[4].positions[2], 0.5, 0.005);
  EXPECT_EQ(script.events.back().points, 4u);
  bool replaced = false, refused = false;
  for (const auto& s : script.said) {
    replaced |= s.rfind("replaced pick:", 0) == 0;
    refused |= s.find("not recorded: ") == 0 && s.find("'lin'") != std::string::npos;
  }
  EXPECT_TRUE(replaced);
  EXPECT_TRUE(refused);

  // A second session adds to the file; its points come back where they were taught.
  Script more;
  more.lines.push_back({[&] { EXPECT_TRUE(hand(0, -0.2)); }, "place"});
  ASSERT_TRUE(teach_points(arm, path, more.io()));
  file = files::read_points_file(path);
  ASSERT_EQ(file->points.size(), 4u);
  std::vector<std::optional<double>> targets;
  for (const auto& j : file->find("pick")->joints) targets.push_back(j.value);
  arm::MoveOptions m;
  m.duration = std::chrono::seconds(1);
  ASSERT_TRUE(arm.move_joints(targets, m));
  ASSERT_TRUE(arm.wait());
  for (std::size_t j = 0; j < 5; ++j) EXPECT_NEAR(here()[j], *targets[j], 0.005);
}

TEST_F(XarmTeach, AnUnreadablePointsFileLeavesTorqueOn) {
  const std::string path = temp_file("bad.points");
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("home joints=banana\n", f);
    std::fclose(f);
  }
  Script script;
  script.lines.push_back({nullptr, ""});
  auto n = teach_points(arm, path, script.io());
  ASSERT_FALSE(n);
  EXPECT_NE(n.error().message.find("bad.points:1:"), std::string::npos) << n.error().message;
  EXPECT_TRUE(servos().torque(1));
  EXPECT_EQ(script.lines.size(), 1u);  // nothing read
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Teaching one point changes that point's line only: the user's comments, blank lines and
// other points stay byte for byte; a new point comes last.
TEST_F(XarmTeach, TeachingKeepsTheFilesCommentsAndOtherLines) {
  const std::string path = temp_file("kept.points");
  const std::string before =
      "# my cell\n"
      "\n"
      "home   joints=0deg,0deg,0deg,0deg,0deg,0deg   # safe\n"
      "place  x=150mm y=70mm z=60mm pitch=50deg  # the tray\n";
  std::ofstream(path, std::ios::binary) << before;
  Script script;
  script.lines.push_back({[&] { EXPECT_TRUE(hand(0, 0.3)); }, "home"});
  script.lines.push_back({nullptr, "pick"});
  ASSERT_TRUE(teach_points(arm, path, script.io()));
  const auto file = files::read_points_file(path).value();
  const std::string home = files::format_point_fields(*file.find("home"));
  const std::string pick = files::format_point_fields(*file.find("pick"));
  EXPECT_NEAR(file.find("home")->joints[0].value, 0.3, 0.005);
  EXPECT_EQ(slurp(path),
            "# my cell\n"
            "\n"
            "home   " + home + "   # safe\n"
            "place  x=150mm y=70mm z=60mm pitch=50deg  # the tray\n"
            "pick  " + pick + "\n");
}

// A read-only points file is the user's "keep this": refused, naming it, before torque goes
// off (nothing typed is read), and left as it was.
TEST_F(XarmTeach, AReadOnlyPointsFileIsRefusedBeforeTorqueOff) {
  const std::string path = temp_file("readonly.points");
  std::ofstream(path, std::ios::binary) << "home joints=0deg\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::group_read |
                                         std::filesystem::perms::others_read);
  Script script;
  script.lines.push_back({nullptr, "pick"});
  auto n = teach_points(arm, path, script.io());
  ASSERT_FALSE(n);
  EXPECT_EQ(n.error().message, "cannot write " + path +
                                   ": it is read-only (mode 0444); make it writable (chmod u+w) to replace it, or "
                                   "write another file");
  for (int id = 1; id <= 6; ++id) EXPECT_TRUE(servos().torque(std::uint8_t(id)));
  EXPECT_EQ(script.lines.size(), 1u);  // nothing read
  EXPECT_EQ(slurp(path), "home joints=0deg\n");
  std::filesystem::remove(path);
}

// A points file that is a symlink (kept in a shared folder, say) is taught through: the
// link stays a link and its target holds the point.
TEST_F(XarmTeach, ASymlinkedPointsFileIsWrittenThrough) {
  const std::string target = temp_file("shared.points"), symlink = temp_file("link.points");
  std::ofstream(target, std::ios::binary) << "# shared\n";
  std::filesystem::create_symlink(target, symlink);
  Script script;
  script.lines.push_back({nullptr, "pick"});
  ASSERT_TRUE(teach_points(arm, symlink, script.io()));
  EXPECT_TRUE(std::filesystem::is_symlink(std::filesystem::symlink_status(symlink)));
  EXPECT_EQ(std::filesystem::read_symlink(symlink), target);
  const auto file = files::read_points_file(target);
  ASSERT_TRUE(file) << file.error().message;
  ASSERT_NE(file->find("pick"), nullptr);
  EXPECT_EQ(slurp(target).rfind("# shared\npick ", 0), 0u) << slurp(target);
  std::filesystem::remove(symlink);
}

TEST_F(XarmTeach, RecordAndReplay) {
  // The hand sweeps joints 1 and 2 over 3 s while it records at 20 Hz.
  const TimePoint start = arm.clock().now();
  RecordOptions o;
  o.rate = 20;
  o.duration = std::chrono::seconds(3);
  o.done = [&] {
    const double t = std::chrono::duration<double>(arm.clock().now() - start).count();
    EXPECT_TRUE(hand(0, 0.6 * std::sin(t * 1.2)));
    EXPECT_TRUE(hand(1, -0.3 * (1 - std::cos(t * 1.5))));
    return false;
  };
  auto r = record_motion(arm, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GE(r->samples.size(), 60u);
  EXPECT_LE(r->samples.size(), 62u);
  EXPECT_TRUE(servos().torque(1));
  // Written and read back.
  const std::string path = temp_file("xarm.rec");
  ASSERT_TRUE(files::write_recording(path, *r));
  auto back = files::read_recording(path);
  ASSERT_TRUE(back) << back.error().message;

  auto plan = plan_replay(arm.model(), here(), *back);
  ASSERT_TRUE(plan) << plan.error().message;
  const double deviation = path_deviation(*back, plan->motion, 6);
  std::printf("xArm replay: %zu samples -> %zu waypoints, duration %.2f s (recorded %.2f s), path deviation %.2f deg\n",
              back->samples.size(), plan->waypoints.size(), plan->motion.duration, plan->recorded_seconds,
              deviation * 180 / M_PI);
  EXPECT_LT(deviation, 0.035);  // 2 deg: smoothing + decimation + quantization (0.24 deg/unit)
  auto to_start = arm::execute_motion(arm, plan->to_start);
  ASSERT_TRUE(to_start) << to_start.error().message;
  auto run = arm::execute_motion(arm, plan->motion);
  ASSERT_TRUE(run) << run.error().message;
  EXPECT_TRUE(run->completed);
  arm.expect_at(back->samples.back().positions);
  ASSERT_TRUE(arm.wait());
  for (std::size_t j = 0; j < 5; ++j) EXPECT_NEAR(here()[j], back->samples.back().positions[j], 0.01);

  // --speed 50 %: never faster, at least twice the recorded time.
  ReplayOptions half;
  half.speed = 0.5;
  auto slow = plan_replay(arm.model(), here(), *back, half);
  ASSERT_TRUE(slow);
  EXPECT_GE(slow->motion.duration, 2 * plan->recorded_seconds - 1e-9);
}

TEST_F(XarmTeach, ReplayRefusesAnotherArmOrOutsideTheLimits) {
  motion::Recording r;
  r.arm = "scara";
  auto other = plan_replay(arm.model(), here(), r);
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().message, "the recording is of arm 'scara', this arm is 'xarm'");
  r.arm = "xarm";
  for (const auto& j : arm.model().joints) r.joints.push_back({j.name, j.dimension});
  r.samples.push_back({0, here()});
  r.samples.push_back({0.05, here()});
  r.samples[1].positions[1] = 3.0;
  auto outside = plan_replay(arm.model(), here(), r);
  ASSERT_FALSE(outside);
  EXPECT_NE(outside.error().message.find("the sample at 0.050 s: joint " + arm.model().joints[1].name + " at 171.887 deg is outside its limits"),
            std::string::npos)
      << outside.error().message;
  r.joints.pop_back();
  EXPECT_NE(plan_replay(arm.model(), here(), r).error().message.find("the recording has 5 joints"), std::string::npos);
}

class ScaraTeach : public ::testing::Test {
 public:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  arm::Arm arm{shipped("scara"),
               std::make_unique<arm::BusArmDevice>(shipped("scara"), master, sim->link(), "simulated SCARA")};
  std::vector<double> here() { return arm.read().value().positions; }
  // A hand's sweep on joint `joint`: rad, or a tenth of it in m (the lift's travel is 300 mm).
  double sweep(int joint, double rad) const {
    return arm.model().joints[std::size_t(joint)].dimension == Dimension::length ? rad / 10 : rad;
  }
  // The hand turns joint `joint` by `si` (rad or m).
  bool turn(int joint, double si) {
    const auto& map = *arm.model().joints[std::size_t(joint)].map(arm::Protocol::joint_bus);
    return sim->joint(map.id).turn_by_hand(si * map.device_per_unit());
  }
};

// At 9600 baud a read of the seven joints takes about 58 ms: 20 Hz is refused at once with
// the rate the link allows (it recorded at 17 Hz under a header saying 20), and a rate the
// link keeps stops at the asked duration (5 s ran 5.83 s).
TEST(ScaraRecording, ARateTheLinkCannotKeepIsRefusedAndTheDurationIsKept) {
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(9600);
  joint_bus::BusMaster master{sim->link()};
  arm::Arm arm{shipped("scara"),
               std::make_unique<arm::BusArmDevice>(shipped("scara"), master, sim->link(), "simulated SCARA")};
  RecordOptions fast;
  fast.rate = 20;
  fast.duration = std::chrono::seconds(2);
  auto refused = record_motion(arm, fast);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("rate 20 Hz is faster than this link allows"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("Hz or less (nothing recorded, torque not switched off)"), std::string::npos);
  for (const auto& j : arm.model().joints) EXPECT_TRUE(sim->joint(j.map(arm::Protocol::joint_bus)->id).controller().loop_enabled());

  RecordOptions kept;
  kept.rate = 10;
  kept.duration = std::chrono::seconds(2);
  auto r = record_motion(arm, kept);
  ASSERT_TRUE(r) << r.error().message;
  // 10 Hz for 2 s: the samples span at most the duration, at the asked spacing.
  EXPECT_GE(r->samples.size(), 20u);
  EXPECT_LE(r->samples.size(), 21u);
  EXPECT_LE(r->samples.back().time, 2.0 + 1e-9);
  EXPECT_NEAR(r->samples.back().time / double(r->samples.size() - 1), 0.1, 0.005);
}

TEST_F(ScaraTeach, PointsFromAScriptLoopsOffThenHolding) {
  const std::string path = temp_file("scara.points");
  const std::vector<double> before = here();
  EXPECT_FALSE(turn(0, 0.2));  // the loop holds the joint
  Script script;
  script.lines.push_back({[&] { EXPECT_TRUE(turn(0, 0.2)); }, "a"});
  script.lines.push_back({[&] { EXPECT_TRUE(turn(1, sweep(1, -0.3))); }, ""});
  auto n = teach_points(arm, path, script.io());
  ASSERT_TRUE(n) << n.error().message;
  EXPECT_EQ(*n, 2u);
  for (const auto& j : arm.model().joints) EXPECT_TRUE(sim->joint(j.map(arm::Protocol::joint_bus)->id).controller().loop_enabled());
  auto file = files::read_points_file(path);
  ASSERT_TRUE(file) << file.error().message;
  ASSERT_EQ(file->points.size(), 2u);
  EXPECT_NEAR(file->points[0].joints[0].value, before[0] + 0.2, 0.002);
  EXPECT_NEAR(file->points[1].joints[1].value, before[1] + sweep(1, -0.3), 0.002);
  const std::vector<double> held = here();
  EXPECT_TRUE(arm.device().idle(std::chrono::seconds(1)));
  for (std::size_t j = 0; j < held.size(); ++j) EXPECT_NEAR(here()[j], held[j], 0.002);
}

TEST_F(ScaraTeach, RecordAndReplay) {
  const std::vector<double> origin = here();
  const TimePoint start = arm.clock().now();
  double turned0 = 0, turned1 = 0;
  RecordOptions o;
  o.rate = 20;
  o.duration = std::chrono::seconds(3);
  o.done = [&] {
    const double t = std::chrono::duration<double>(arm.clock().now() - start).count();
    const double want0 = sweep(0, 0.5 * std::sin(t)), want1 = sweep(1, 0.4 * (1 - std::cos(t * 1.3)));
    EXPECT_TRUE(turn(0, want0 - turned0));
    EXPECT_TRUE(turn(1, want1 - turned1));
    turned0 = want0;
    turned1 = want1;
    return false;
  };
  auto r = record_motion(arm, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GE(r->samples.size(), 60u);
  const std::vector<double> end = here();
  EXPECT_NEAR(end[0], origin[0] + turned0, 0.002);
  // Back to the origin by hand with the loops off, then replay from there.
  Script back_home;
  back_home.lines.push_back({[&] { EXPECT_TRUE(turn(0, -turned0)); EXPECT_TRUE(turn(1, -turned1)); }, "origin"});
  ASSERT_TRUE(teach_points(arm, temp_file("scara2.points"), back_home.io()));
  auto plan = plan_replay(arm.model(), here(), *r);
  ASSERT_TRUE(plan) << plan.error().message;
  const double deviation = path_deviation(*r, plan->motion, r->joints.size());
  std::printf("SCARA replay: %zu samples -> %zu waypoints, duration %.2f s (recorded %.2f s), path deviation %.2f deg\n",
              r->samples.size(), plan->waypoints.size(), plan->motion.duration, plan->recorded_seconds,
              deviation * 180 / M_PI);
  EXPECT_LT(deviation, 0.02);
  ASSERT_TRUE(arm::execute_motion(arm, plan->to_start));
  auto run = arm::execute_motion(arm, plan->motion);
  ASSERT_TRUE(run) << run.error().message;
  std::printf("SCARA replay executed: largest following error %.3f (SI) on joint %d\n", run->largest_following_error,
              run->largest_following_joint);
  arm.expect_at(r->samples.back().positions);
  arm::WaitOptions w;
  w.timeout = std::chrono::seconds(5);
  ASSERT_TRUE(arm.wait(w));
  for (std::size_t j = 0; j < 2; ++j) EXPECT_NEAR(here()[j], r->samples.back().positions[j], 0.005);
}

}  // namespace
}  // namespace armctl::teach
