// The flow of a program (program/program_flow.hpp): variables, units, IF, loops,
// subroutines with parameters, PRINT, OVERRIDE, and every run-time error with its place.
#include <gtest/gtest.h>

#include <numbers>

#include "core/source_place.hpp"
#include "program/program_flow.hpp"
#include "program/program_parser.hpp"

namespace armctl::program {
namespace {

files::PointsFile points() {
  return files::parse_points_file("home joints=0deg,0deg\np x=200mm y=0mm z=50mm pitch=90deg\nq x=150mm y=50mm z=50mm\n").value();
}

Result<Flow> flow_of(std::string_view text, const FlowLimits& limits = {}) {
  auto p = parse_program(text, "f.prog");
  if (!p) return p.error();
  return run_flow(*p, points(), limits);
}

Flow flow(std::string_view text) {
  auto f = flow_of(text);
  EXPECT_TRUE(f.ok()) << (f ? "" : f.error().message);
  return f ? std::move(f).value() : Flow{};
}

// Every such error carries its place (SourcePlace) and its message is that place's rendering.
void expect_placed(const Error& e) {
  const SourcePlace* at = source_place(e);
  ASSERT_NE(at, nullptr) << e.message;
  EXPECT_EQ(source_error(e.kind, *at).message, e.message);
}

std::string error_of(std::string_view text, const FlowLimits& limits = {}) {
  auto f = flow_of(text, limits);
  EXPECT_FALSE(f.ok()) << text;
  if (!f) expect_placed(f.error());
  return f ? "" : f.error().message;
}

std::vector<std::string> prints(const Flow& f) {
  std::vector<std::string> out;
  for (const auto& a : f.actions)
    if (a.kind == ActionKind::print) out.push_back(a.text);
  return out;
}

TEST(ProgramFlow, ArithmeticWithUnitsAndComparisons) {
  const Flow f = flow(
      "a = 40mm + 2cm\n"
      "b = a * 2 / 4\n"
      "c = 90deg - 0.5rad\n"
      "r = a / b\n"
      "print a, \" \", b, \" \", c, \" \", r, \" \", 50% * 40mm/s\n"
      "print 3 < 4, 4 <= 3, a == 60mm, a != 60mm, 1 and 0, 1 or 0, not 0, -a\n");
  EXPECT_EQ(prints(f), (std::vector<std::string>{"60 mm 30 mm 61.3521 deg 2 20 mm/s", "1010011-60 mm"}));
}

TEST(ProgramFlow, IfLoopWhileAndSubroutinesWithParameters) {
  const Flow f = flow(
      "def show(x)\n"
      "  print \"t=\", x\n"
      "  x = x + 1\n"            // a parameter is the subroutine's own
      "  total = total + x\n"    // a global is changed where it lives
      "end\n"
      "total = 0\n"
      "loop 3 times\n"
      "  call show(total)\n"
      "end\n"
      "n = 0\n"
      "while n < 2\n"
      "  n = n + 1\n"
      "end\n"
      "if total > 5 then\n"
      "  print \"big \", total\n"
      "else\n"
      "  print \"small \", total\n"
      "end\n"
      "loop 0 times\n"
      "  print \"never\"\n"
      "end\n"
      "print n\n");
  EXPECT_EQ(prints(f), (std::vector<std::string>{"t=0", "t=1", "t=3", "big 7", "2"}));
}

TEST(ProgramFlow, MovesCarryTheirNumbersAndTheOverride) {
  const Flow f = flow(
      "h = 30mm\n"
      "ptp home speed=50% accel=20%\n"
      "override 50%\n"
      "lin p + tool(z=-h) speed=40mm/s zone=5mm accel=0.5m/s^2 angular_speed=20deg/s\n"
      "circ q, pose(x=100mm, y=0mm, z=h * 2, elbow=up)\n"
      "ptp joints(10deg, 20mm)\n"
      "wait 0.25s\n"
      "gripper open\n"
      "gripper 25%\n"
      "gripper close\n");
  ASSERT_EQ(f.actions.size(), 8u);
  const MoveAction& ptp = f.actions[0].move;
  EXPECT_EQ(ptp.kind, MoveKind::ptp);
  EXPECT_DOUBLE_EQ(*ptp.speed, 0.5);
  EXPECT_DOUBLE_EQ(*ptp.acceleration, 0.2);
  EXPECT_EQ(ptp.target.label, "home");
  EXPECT_DOUBLE_EQ(ptp.override_fraction, 1);
  const MoveAction& lin = f.actions[1].move;
  EXPECT_EQ(lin.target.offset_frame, OffsetFrame::tool);
  EXPECT_NEAR(lin.target.offset.z(), -0.03, 1e-15);
  EXPECT_NEAR(*lin.speed, 0.04, 1e-15);
  EXPECT_NEAR(lin.zone, 0.005, 1e-15);
  EXPECT_NEAR(*lin.angular_speed, 20 * std::numbers::pi / 180, 1e-15);
  EXPECT_DOUBLE_EQ(lin.override_fraction, 0.5);
  const MoveAction& circ = f.actions[2].move;
  ASSERT_TRUE(circ.via);
  EXPECT_EQ(circ.via->label, "q");
  EXPECT_NEAR(circ.target.position.z(), 0.06, 1e-15);
  EXPECT_EQ(circ.target.elbow, motion::Elbow::up);
  EXPECT_EQ(f.actions[3].move.target.joints[1].dimension, Dimension::length);
  EXPECT_EQ(f.actions[4].kind, ActionKind::wait);
  EXPECT_DOUBLE_EQ(f.actions[4].seconds, 0.25);
  EXPECT_DOUBLE_EQ(f.actions[5].closed_fraction, 0);
  EXPECT_DOUBLE_EQ(f.actions[6].closed_fraction, 0.25);
  EXPECT_DOUBLE_EQ(f.actions[7].closed_fraction, 1);
  EXPECT_EQ(f.actions[7].at.line, 10u);
}

TEST(ProgramFlow, NamesResolveBeforeAnythingRuns) {
  // Even in a branch that never runs.
  EXPECT_EQ(error_of("if 0\n  ptp nowhere\nend\n"),
            "f.prog:2:7: found point 'nowhere', expected a point of the points file (it has home, p, q)");
  EXPECT_EQ(error_of("call pick(1)\n"),
            "f.prog:1:1: found CALL pick, expected a subroutine defined with DEF (the program defines none)");
  EXPECT_EQ(error_of("def pick(a, b)\nend\ncall pick(1)\n"),
            "f.prog:3:1: found 1 argument to pick, expected 2 (DEF pick at line 1)");
}

TEST(ProgramFlow, ValuesOfTheWrongKindAreRefusedWithTheirPlace) {
  EXPECT_EQ(error_of("wait 2\n"), "f.prog:1:6: WAIT takes a time (e.g. 0.5s), found a plain number (2)");
  EXPECT_EQ(error_of("wait -1s\n"), "f.prog:1:6: WAIT is -1 s; allowed 0 s up to 3600 s");
  EXPECT_EQ(error_of("lin p speed=50%\n"), "f.prog:1:13: LIN's speed takes a speed (e.g. 40mm/s), found a percentage (50 %)");
  EXPECT_EQ(error_of("ptp p speed=0%\n"), "f.prog:1:13: PTP's speed is 0 %; allowed 0.1 % up to 100 %");
  // Speeds of 1e-300 were accepted and answered later about internal quantities.
  EXPECT_EQ(error_of("ptp p speed=1e-300%\n"), "f.prog:1:13: PTP's speed is 1e-300 %; allowed 0.1 % up to 100 %");
  EXPECT_EQ(error_of("lin p speed=1e-300mm/s\n"),
            "f.prog:1:13: LIN's speed is 1e-300 mm/s; allowed 0.1 mm/s up to 500 mm/s");
  EXPECT_EQ(error_of("lin p speed=2m/s\n"), "f.prog:1:13: LIN's speed is 2000 mm/s; allowed 0.1 mm/s up to 500 mm/s");
  EXPECT_EQ(error_of("lin p angular_speed=1e-300deg/s\n"),
            "f.prog:1:21: LIN's angular_speed is 1e-300 deg/s; allowed 0.1 deg/s up to 720 deg/s");
  EXPECT_EQ(error_of("override 1e-300%\n"), "f.prog:1:10: OVERRIDE is 1e-300 %; allowed 0.1 % up to 100 %");
  EXPECT_EQ(error_of("override 0.5\n"), "f.prog:1:10: OVERRIDE takes a percentage (e.g. 50%), found a plain number (0.5)");
  EXPECT_EQ(error_of("ptp pose(x=200, y=0mm, z=0mm)\n"),
            "f.prog:1:12: x takes a length (e.g. 40mm), found a plain number (200)");
  EXPECT_EQ(error_of("n = 40mm + 1deg\n"),
            "f.prog:1:10: '+' adds a length and an angle (40 mm + 1 deg); both sides need the same kind of value");
  EXPECT_EQ(error_of("n = 40mm * 1deg\n"),
            "f.prog:1:10: '*' of a length by an angle: one side must be a plain number or a percentage");
  EXPECT_EQ(error_of("n = 1 / (2 - 2)\n"), "f.prog:1:7: division by zero (1 / 0)");
  EXPECT_EQ(error_of("n = m + 1\n"), "f.prog:1:5: 'm' has no value here; give it one first (e.g. m = 3)");
  EXPECT_EQ(error_of("if 3mm\nend\n"), "f.prog:1:4: IF takes a condition (e.g. n < 3), found a length (3 mm)");
  EXPECT_EQ(error_of("loop 2.5 times\nend\n"), "f.prog:1:6: LOOP's count is 2.5; it must be a whole number");
  EXPECT_EQ(error_of("gripper 150%\n"), "f.prog:1:9: GRIPPER is 150 %; allowed 0 % up to 100 %");
  EXPECT_EQ(error_of("override 0%\n"), "f.prog:1:10: OVERRIDE is 0 %; allowed 0.1 % up to 100 %");
  EXPECT_EQ(error_of("ptp joints(10deg, 5)\n"),
            "f.prog:1:19: a joint value is an angle or a length (e.g. 30deg, 120mm), found a plain number (5)");
  EXPECT_EQ(error_of("n = 1e300 * 1e300\n"), "f.prog:1:11: '*' overflows (1e+300 * 1e+300)");
  // A subroutine's parameters are not visible outside it.
  EXPECT_EQ(error_of("def a(x)\nend\ncall a(1)\nprint x\n"), "f.prog:4:7: 'x' has no value here; give it one first (e.g. x = 3)");
}

TEST(ProgramFlow, LoopsAndCallsAreBounded) {
  FlowLimits small;
  small.loop_iterations = 100;
  EXPECT_EQ(error_of("n = 0\nwhile n < 1\n  n = n * 2\nend\n", small),
            "f.prog:2:1: the WHILE ran 100 times and its condition still holds; a loop may run at most 100 times (the "
            "check runs the flow to plan every move)");
  EXPECT_EQ(error_of("loop 101 times\nend\n", small), "f.prog:1:6: LOOP's count is 101; allowed 0 up to 100");
  EXPECT_EQ(error_of("def a()\n  call a()\nend\ncall a()\n"),
            "f.prog:2:3: subroutines call one another more than 64 deep (a CALL that never ends?)");
  FlowLimits few;
  few.actions = 5;
  EXPECT_EQ(error_of("loop 10 times\n  wait 0s\nend\n", few),
            "f.prog:2:3: the program performs more than 5 moves, waits, gripper moves and prints; that is the most one "
            "run may do (a loop that never ends?)");
}

// A left-deep chain far longer than the parser lets through (built here by hand): the flow
// evaluates it by a loop and the tree frees itself by one; recursing per term overflowed the
// stack at some 50,000 terms.
TEST(ProgramFlow, LongChainsAreEvaluatedWithoutRecursion) {
  auto literal = [](double v) {
    auto e = std::make_unique<Expr>();
    e->value = {v, Unit::number};
    e->at = {1, 5};
    return e;
  };
  ExprPtr sum = literal(1);
  for (int i = 0; i < 300'000; ++i) {
    auto e = std::make_unique<Expr>();
    e->kind = ExprKind::binary;
    e->op = i % 2 ? Operator::add : Operator::sub;
    e->at = {1, 7};
    e->left = std::move(sum);
    e->right = literal(i % 2 ? 3 : 1);
    sum = std::move(e);
  }
  Program p;
  p.source = "f.prog";
  Statement assign;
  assign.kind = StatementKind::assign;
  assign.name = "n";
  assign.value = std::move(sum);
  p.main.push_back(std::move(assign));
  Statement print;
  print.kind = StatementKind::print;
  print.at = {2, 1};
  PrintItem item;
  item.value = std::make_unique<Expr>();
  item.value->kind = ExprKind::variable;
  item.value->name = "n";
  print.print.push_back(std::move(item));
  p.main.push_back(std::move(print));
  auto f = run_flow(p, points());
  ASSERT_TRUE(f.ok()) << f.error().message;
  // 1, then 150,000 times (- 1 + 3): 300,001.
  EXPECT_EQ(prints(*f), std::vector<std::string>{"300001"});
}

}  // namespace
}  // namespace armctl::program
