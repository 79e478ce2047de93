// Programs on both simulated arms, on simulated time: the shipped pick-and-place examples
// checked and run, blends and what breaks them, WAIT, stop and override; the check
// refusing an unreachable move before any byte is sent; compile-to-group replayed on the
// emulated board within the stated path error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "core/source_place.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "program/group_compiler.hpp"
#include "program/program_parser.hpp"
#include "program/program_plan.hpp"
#include "program/program_runner.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::program {
namespace {

using arm::testing::shipped;

std::string example(const std::string& name) { return std::string(ARMCTL_SOURCE_DIR) + "/examples/programs/" + name; }

Flow flow_of(std::string_view text, std::string_view points_text) {
  auto program = parse_program(text, "t.prog");
  EXPECT_TRUE(program) << program.error().message;
  auto points = files::parse_points_file(points_text, "t.points");
  EXPECT_TRUE(points) << points.error().message;
  auto flow = run_flow(*program, *points);
  EXPECT_TRUE(flow) << flow.error().message;
  return flow ? std::move(flow).value() : Flow{};
}

Flow example_flow(const std::string& arm) {
  auto program = read_program_file(example(arm + "-pick-place.prog"));
  EXPECT_TRUE(program) << program.error().message;
  auto points = files::read_points_file(example(arm + "-pick-place.points"));
  EXPECT_TRUE(points) << points.error().message;
  auto flow = run_flow(*program, *points);
  EXPECT_TRUE(flow) << flow.error().message;
  return std::move(flow).value();
}

// The distance from `p` to the segment a..b.
double to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double f = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + f * d)).norm();
}

// The nearest distance from `p` to the polyline through `path`.
double to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& path) {
  double best = 1e9;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) best = std::min(best, to_segment(p, path[i], path[i + 1]));
  return best;
}

class XarmProgram : public ::testing::Test {
 public:
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  arm::Arm arm{shipped("xarm"), std::make_unique<arm::RcArmDevice>(shipped("xarm"), client)};

  std::vector<double> here() { return arm.read().value().positions; }
  std::vector<double> true_joints() {
    std::vector<double> device;
    for (const auto& j : arm.model().joints)
      device.push_back(link.emulator().servos().commanded_position(std::uint8_t(j.map(arm::Protocol::robot_commands)->id)));
    return arm.model().from_device(arm::Protocol::robot_commands, device);
  }
  Eigen::Vector3d true_tool() { return arm.forward(arm.chain_of(true_joints())).position; }
  double seconds() const { return std::chrono::duration<double>(arm.clock().now().time_since_epoch()).count(); }
};

class ScaraProgram : public ::testing::Test {
 public:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  arm::Arm arm{shipped("scara"),
               std::make_unique<arm::BusArmDevice>(shipped("scara"), master, sim->link(), "simulated SCARA")};

  std::vector<double> here() { return arm.read().value().positions; }
  Eigen::Vector3d true_tool() {
    std::vector<double> device;
    for (const auto& j : arm.model().joints) device.push_back(sim->joint(j.map(arm::Protocol::joint_bus)->id).controller().position());
    return arm.forward(arm.chain_of(arm.model().from_device(arm::Protocol::joint_bus, device))).position;
  }
};

// The example: every part picked at `pick` and stacked at `place`, the tool passing over
// both within `tolerance`; three PRINTs of progress and the gripper used each time.
template <typename Rig>
void run_example(Rig& rig, const std::string& name, double tolerance) {
  const Flow flow = example_flow(name);
  auto plan = plan_program(*rig.arm.kinematics(), rig.here(), flow, name);
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_GT(plan->duration, 5.0);
  auto points = files::read_points_file(example(name + "-pick-place.points")).value();
  const Eigen::Vector3d pick = points.find("pick")->position, place = points.find("place")->position;
  double nearest_pick = 1e9, nearest_place = 1e9;
  std::vector<std::string> printed;
  RunOptions o;
  o.on_event = [&](const RunEvent& e) {
    if (e.kind == RunEventKind::message) printed.push_back(e.piece->text);
    const Eigen::Vector3d t = rig.true_tool();
    nearest_pick = std::min(nearest_pick, (t - pick).norm());
    // The first part is placed at the point's own height, the others above it.
    nearest_place = std::min(nearest_place, (t - place).norm());
  };
  auto r = run_plan(rig.arm, *plan, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  EXPECT_EQ(r->pieces, plan->pieces.size());
  EXPECT_LT(nearest_pick, tolerance);
  EXPECT_LT(nearest_place, tolerance);
  ASSERT_GE(printed.size(), 3u);
  EXPECT_EQ(printed[0], "placed part 1 of 3");
  EXPECT_EQ(printed[2], "placed part 3 of 3");
  // It ran about as long as planned (the executor's ramps and read-backs add a little).
  const double elapsed = std::chrono::duration<double>(r->elapsed).count();
  EXPECT_GT(elapsed, plan->duration * 0.95);
  EXPECT_LT(elapsed, plan->duration * 1.3 + 1);
}

TEST_F(XarmProgram, RunsThePickAndPlaceExample) { run_example(*this, "xarm", 0.004); }
TEST_F(ScaraProgram, RunsThePickAndPlaceExample) { run_example(*this, "scara", 0.004); }

TEST_F(XarmProgram, CheckRefusesAnUnreachableMoveBeforeAnyByteIsSent) {
  const Flow flow = flow_of(
      "ptp home\n"
      "lin home + base(z=-20mm)\n"
      "lin far speed=40mm/s\n",
      // Within the xArm's reach bound (366 mm from its base), beyond where it reaches with
      // this pitch: the path check finds where (farther points are refused before planning).
      "home x=180mm y=0mm z=100mm pitch=50deg\nfar x=340mm y=0mm z=100mm pitch=50deg\n");
  const auto start = here();
  const std::size_t sent = link.sent.size();
  auto plan = plan_program(*arm.kinematics(), start, flow, "t.prog");
  ASSERT_FALSE(plan);
  EXPECT_EQ(plan.error().kind, ErrorKind::invalid_argument);
  // The line of the move that fails, its kind and target, and the path check's reason.
  EXPECT_EQ(plan.error().message.rfind("t.prog:3: (LIN far): at ", 0), 0u) << plan.error().message;
  // Placed by its detail: the program's file and the line of the segment the path check named.
  const SourcePlace* at = source_place(plan.error());
  ASSERT_NE(at, nullptr);
  EXPECT_EQ(at->file, "t.prog");
  EXPECT_EQ(at->line, 3u);
  EXPECT_EQ(at->reason.rfind("(LIN far): at ", 0), 0u) << at->reason;
  EXPECT_EQ(link.sent.size(), sent);
  // Beyond any reach: refused before planning, with the coordinate and the reach.
  const Flow beyond = flow_of("lin far speed=40mm/s\n", "far x=600mm y=0mm z=100mm pitch=50deg\n");
  EXPECT_EQ(plan_program(*arm.kinematics(), start, beyond, "t.prog").error().message,
            "t.prog:1: (LIN far): target: x 600 mm is beyond reach: arm 'xarm' reaches at most 366 mm from its base");
  // A PTP to a point out of reach: the IK's reason.
  const Flow ptp = flow_of("ptp far\n", "far x=600mm y=0mm z=100mm\n");
  auto refused = plan_program(*arm.kinematics(), start, ptp, "t.prog");
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message.rfind("t.prog:1: (PTP far): ", 0), 0u) << refused.error().message;
  // Joint values outside the limits, with the joint named.
  const Flow joints = flow_of("ptp joints(150deg)\n", "");
  auto outside = plan_program(*arm.kinematics(), start, joints, "t.prog");
  ASSERT_FALSE(outside);
  EXPECT_NE(outside.error().message.find("servo6"), std::string::npos) << outside.error().message;
  // A length for a revolute joint, and more values than the arm has joints.
  auto wrong_kind = plan_program(*arm.kinematics(), start, flow_of("ptp joints(10deg, 20mm)\n", ""), "t.prog");
  ASSERT_FALSE(wrong_kind);
  EXPECT_NE(wrong_kind.error().message.find("joint servo5 takes an angle, not a length"), std::string::npos)
      << wrong_kind.error().message;
  auto too_many = plan_program(*arm.kinematics(), start, flow_of("ptp joints(0deg, 0deg, 0deg, 0deg, 0deg, 0deg, 0deg)\n", ""),
                               "t.prog");
  ASSERT_FALSE(too_many);
  EXPECT_NE(too_many.error().message.find("7 joint values given; arm 'xarm' has 6 joints"), std::string::npos)
      << too_many.error().message;
  EXPECT_EQ(link.sent.size(), sent);
}

TEST_F(XarmProgram, ConsecutiveCartesianMovesBlendAndEverythingElseBreaksTheBlend) {
  const std::string points = "a x=180mm y=-40mm z=100mm pitch=50deg\nb x=180mm y=40mm z=100mm pitch=50deg\n"
                             "c x=120mm y=40mm z=100mm pitch=50deg\n";
  const std::string moves = "lin b speed=40mm/s zone=10mm\nlin c speed=40mm/s zone=10mm\nlin a speed=40mm/s\n";
  const auto start = here();
  auto count = [&](const std::string& text, bool blend) {
    PlanOptions o;
    o.blend = blend;
    auto plan = plan_program(*arm.kinematics(), start, flow_of(text, points), "t.prog", o);
    EXPECT_TRUE(plan) << plan.error().message;
    std::size_t motions = 0;
    for (const auto& p : plan->pieces) motions += p.kind == PieceKind::motion;
    return motions;
  };
  // The PTP is a piece of its own; the three LINs one path (loops and calls between them
  // do not break it).
  EXPECT_EQ(count("ptp a\n" + moves, true), 2u);
  EXPECT_EQ(count("ptp a\ndef go()\n  lin b speed=40mm/s zone=10mm\nend\nloop 2 times\n  call go()\n  lin c zone=5mm\nend\n", true), 2u);
  EXPECT_EQ(count("ptp a\nlin b zone=10mm\nwait 0s\nlin c\n", true), 3u);
  EXPECT_EQ(count("ptp a\nlin b zone=10mm\nprint \"x\"\nlin c\n", true), 3u);
  EXPECT_EQ(count("ptp a\nlin b zone=10mm\ngripper close\nlin c\n", true), 4u);
  EXPECT_EQ(count("ptp a\nlin b zone=10mm\nptp c\nlin a\n", true), 4u);
  // --step: every move on its own.
  EXPECT_EQ(count("ptp a\n" + moves, false), 4u);
  // A blended path is faster than the same moves stopping at every corner.
  auto blended = plan_program(*arm.kinematics(), start, flow_of("ptp a\n" + moves, points), "t.prog").value();
  PlanOptions stepwise;
  stepwise.blend = false;
  auto stopped = plan_program(*arm.kinematics(), start, flow_of("ptp a\n" + moves, points), "t.prog", stepwise).value();
  EXPECT_LT(blended.duration, stopped.duration - 0.2);
}

TEST_F(XarmProgram, WaitTakesItsTimeOnTheDeviceClock) {
  const Flow flow = flow_of("wait 1.5s\nwait 250ms\n", "");
  auto plan = plan_program(*arm.kinematics(), here(), flow, "t.prog").value();
  EXPECT_DOUBLE_EQ(plan.duration, 1.75);
  const double before = seconds();
  auto r = run_plan(arm, plan);
  ASSERT_TRUE(r) << r.error().message;
  // Never shorter; the run ends with a closed-loop wait (a few position reads) on top.
  EXPECT_GE(seconds() - before, 1.75);
  EXPECT_LT(seconds() - before, 2.1);
}

TEST_F(XarmProgram, OverrideSlowsTheMotionsAndStopComesToRest) {
  const std::string points = "a x=180mm y=-40mm z=100mm pitch=50deg\nb x=180mm y=40mm z=100mm pitch=50deg\n";
  const Flow flow = flow_of("ptp a\nlin b speed=40mm/s\n", points);
  auto plan = plan_program(*arm.kinematics(), here(), flow, "t.prog").value();
  RunOptions half;
  half.speed_override = 0.5;
  auto r = run_plan(arm, plan, half);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GT(std::chrono::duration<double>(r->elapsed).count(), 1.8 * plan.duration);
  // Back to a, then stop half way along the LIN: the arm rests on the line, short of b.
  auto back = plan_program(*arm.kinematics(), here(), flow_of("ptp a\nlin b speed=40mm/s\n", points), "t.prog").value();
  const double stop_at = seconds() + back.pieces[0].motion.duration + 1.0;
  RunOptions o;
  o.command = [&] { return seconds() > stop_at ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  auto stopped = run_plan(arm, back, o);
  ASSERT_TRUE(stopped) << stopped.error().message;
  EXPECT_FALSE(stopped->completed);
  EXPECT_EQ(stopped->pieces, 1u);
  ASSERT_TRUE(arm.wait());
  const auto pts = files::parse_points_file(points).value();
  const Eigen::Vector3d a = pts.find("a")->position, b = pts.find("b")->position;
  const Eigen::Vector3d t = true_tool();
  EXPECT_LT(to_polyline(t, {a, b}), 0.003);
  EXPECT_GT((t - b).norm(), 0.01);
}

TEST_F(ScaraProgram, ToolOffsetsAreInTheToolFrame) {
  // The SCARA's tool points down (roll 180 deg): +z of the tool is -z of the base.
  const Flow flow = flow_of("ptp p\nlin p + tool(z=30mm) speed=50mm/s\n",
                            "p x=420mm y=0mm z=300mm roll=180deg pitch=0deg yaw=0deg\n");
  auto plan = plan_program(*arm.kinematics(), here(), flow, "t.prog");
  ASSERT_TRUE(plan) << plan.error().message;
  auto r = run_plan(arm, *plan);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_LT((true_tool() - Eigen::Vector3d(0.42, 0, 0.27)).norm(), 0.002);
}

TEST_F(XarmProgram, CompiledGroupReplaysOnTheBoardWithinThePathError) {
  const Flow flow = example_flow("xarm");
  auto plan = plan_program(*arm.kinematics(), here(), flow, "xarm").value();
  CompileOptions co;
  co.path_error = 0.001;
  auto group = compile_to_group(arm, plan, co);
  ASSERT_TRUE(group) << group.error().message;
  EXPECT_LE(group->actions.size(), 1020u);
  EXPECT_LE(group->sampling_error, co.path_error);
  EXPECT_NEAR(group->duration, plan.duration + co.first_move_seconds, 0.05);
  // PRINTs are left out, and said so.
  EXPECT_FALSE(group->notes.empty());
  // The plan's tool path, finely.
  std::vector<Eigen::Vector3d> planned;
  for (const auto& piece : plan.pieces) {
    if (piece.kind != PieceKind::motion) continue;
    std::vector<double> q(6), v(6), a(6);
    for (double t = 0; t <= piece.motion.duration; t += 0.002) {
      piece.motion.sample(t, q, v, a);
      planned.push_back(arm.forward(arm.chain_of(q)).position);
    }
  }
  ASSERT_TRUE(client.download_group(3, group->actions));
  ASSERT_TRUE(client.run_group(3, 1));
  // The board replays it alone: sample the servos every 10 ms of its time (receive() lets
  // the link deliver the run command and moves the board's time on).
  double worst = 0;
  const double quantization = arm::tool_quantization(arm.model(), arm::Protocol::robot_commands, plan.start);
  const double end = seconds() + group->duration + 0.5;
  int samples = 0;
  // Skip the first action (from wherever the servos are to the start).
  const double from = seconds() + co.first_move_seconds + 0.05;
  // The replay moves forward along the plan: each sample is compared with the plan's path
  // from where the previous one matched to 2 s further on (the program passes the same
  // places several times; a global nearest point could be another pass).
  std::size_t cursor = 0;
  while (seconds() < end) {
    (void)link.receive(link.clock().now() + std::chrono::milliseconds(10));
    if (seconds() < from) continue;
    const Eigen::Vector3d tool = true_tool();
    double nearest = 1e9;
    std::size_t best = cursor;
    for (std::size_t j = cursor; j + 1 < planned.size() && j < cursor + 1000; ++j) {
      const double d = to_segment(tool, planned[j], planned[j + 1]);
      if (d < nearest) {
        nearest = d;
        best = j;
      }
    }
    cursor = best;
    worst = std::max(worst, nearest);
    ++samples;
  }
  EXPECT_GT(samples, 1000);
  // It went all the way: the servos end where the plan does.
  EXPECT_LT((true_tool() - planned.back()).norm(), co.path_error + quantization);
  EXPECT_GT(cursor + 200, planned.size());  // its last 0.4 s are at rest at the end
  // Sampling error plus the servo units' quantization.
  EXPECT_LT(worst, co.path_error + quantization) << "quantization " << quantization * 1e3 << " mm";
  RecordProperty("replay_path_error_mm", std::to_string(worst * 1e3));
  std::printf("compiled %zu actions; replay within %.3f mm of the plan's path (allowed %.3f + %.3f mm)\n",
              group->actions.size(), worst * 1e3, co.path_error * 1e3, quantization * 1e3);
}

TEST(ProgramCompile, RefusesAnArmWithoutRobotCommandsServosAndTooManyActions) {
  auto sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  arm::ArmModel model = shipped("scara");
  for (auto& j : model.joints) j.devices.erase("robot_commands");
  arm::Arm arm{model, std::make_unique<arm::BusArmDevice>(model, master, sim->link(), "simulated SCARA")};
  ProgramPlan plan;
  plan.start = arm.read().value().positions;
  auto g = compile_to_group(arm, plan);
  ASSERT_FALSE(g);
  EXPECT_EQ(g.error().kind, ErrorKind::unsupported);
}

}  // namespace
}  // namespace armctl::program
