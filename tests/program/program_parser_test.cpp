// The program parser (program/program_parser.hpp): every statement form, and for every
// kind of mistake the exact message with file, line and column, what was found and what
// was expected.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>
#include <fmt/core.h>

#include "core/source_place.hpp"
#include "program/program_parser.hpp"

namespace armctl::program {
namespace {

Program parsed(std::string_view text) {
  auto p = parse_program(text, "t.prog");
  EXPECT_TRUE(p.ok()) << (p ? "" : p.error().message);
  return p ? std::move(p).value() : Program{};
}

// Every such error carries its place (SourcePlace) and its message is that place's rendering.
void expect_placed(const Error& e) {
  const SourcePlace* at = source_place(e);
  ASSERT_NE(at, nullptr) << e.message;
  EXPECT_EQ(source_error(e.kind, *at).message, e.message);
}

std::string error_of(std::string_view text) {
  auto p = parse_program(text, "t.prog");
  EXPECT_FALSE(p.ok()) << text;
  if (p) return "";
  EXPECT_EQ(p.error().kind, ErrorKind::invalid_config);
  expect_placed(p.error());
  return p.error().message;
}

TEST(ProgramParser, Moves) {
  const Program p = parsed(
      "PTP home speed=50% accel=30%\n"
      "lin pick + tool(z=-30mm) speed=40mm/s accel=500mm/s^2 zone=5mm angular_speed=30deg/s\n"
      "Circ side, pose(x=200mm, y=0mm, z=50mm, pitch=90deg, elbow=up)\n"
      "ptp joints(0deg, 30deg, -0.5rad)\n"
      "lin pick + base(x=10mm, y=-1cm)\n");
  ASSERT_EQ(p.main.size(), 5u);
  EXPECT_EQ(p.main[0].move, MoveKind::ptp);
  EXPECT_EQ(p.main[0].target.point, "home");
  EXPECT_EQ(p.main[0].options.size(), 2u);
  EXPECT_EQ(p.main[1].target.offset_frame, OffsetFrame::tool);
  EXPECT_EQ(p.main[1].options.size(), 4u);
  EXPECT_EQ(p.main[2].move, MoveKind::circ);
  ASSERT_TRUE(p.main[2].via);
  EXPECT_EQ(p.main[2].via->point, "side");
  EXPECT_EQ(p.main[2].target.kind, TargetKind::pose);
  EXPECT_EQ(p.main[2].target.pose.size(), 5u);
  EXPECT_EQ(p.main[2].target.pose[4].word, "up");
  EXPECT_EQ(p.main[3].target.kind, TargetKind::joints);
  EXPECT_EQ(p.main[3].target.joints.size(), 3u);
  EXPECT_NEAR(p.main[3].target.joints[1]->value.si, std::numbers::pi / 6, 1e-12);
  EXPECT_EQ(p.main[4].target.offset_frame, OffsetFrame::base);
  EXPECT_EQ(p.main[4].at.line, 5u);
}

TEST(ProgramParser, FlowAndSubroutines) {
  const Program p = parsed(
      "# a comment line\n"
      "def pick(height, speed)   # trailing comment\n"
      "  lin p + base(z=height) speed=speed\n"
      "end\n"
      "n = 0\n"
      "loop 3 times\n"
      "  call pick(40mm, 20mm/s)\n"
      "  n = n + 1\n"
      "end\n"
      "while n < 5 and not n == 4\n"
      "  n = (n + 1) * 2 - -1\n"
      "end\n"
      "if n >= 2 then\n"
      "  print \"n is \", n\n"
      "else\n"
      "  wait 500ms\n"
      "end\n"
      "gripper close\n"
      "gripper 40%\n"
      "override 50%\n");
  ASSERT_EQ(p.subroutines.size(), 1u);
  EXPECT_EQ(p.subroutines[0].parameters, (std::vector<std::string>{"height", "speed"}));
  ASSERT_EQ(p.main.size(), 7u);
  EXPECT_EQ(p.main[1].kind, StatementKind::loop);
  EXPECT_EQ(p.main[1].body.size(), 2u);
  EXPECT_EQ(p.main[2].kind, StatementKind::while_);
  EXPECT_EQ(p.main[3].kind, StatementKind::if_);
  EXPECT_EQ(p.main[3].otherwise.size(), 1u);
  EXPECT_EQ(p.main[3].body[0].print.size(), 2u);
  EXPECT_EQ(p.main[4].gripper, GripperAction::close);
  EXPECT_EQ(p.main[5].gripper, GripperAction::to);
  EXPECT_EQ(p.main[6].kind, StatementKind::override_);
}

TEST(ProgramParser, EveryErrorSaysWhereWhatAndWhatWasExpected) {
  EXPECT_EQ(error_of("jump home\n"),
            "t.prog:1:1: found 'jump', expected a statement: PTP, LIN, CIRC, WAIT, GRIPPER, PRINT, IF, LOOP, WHILE, "
            "CALL, OVERRIDE, DEF or NAME = value");
  EXPECT_EQ(error_of("ptp\n"),
            "t.prog:1:4: found the end of the line, expected the PTP's target: a point name, pose(x=.., y=.., z=..) or "
            "joints(..)");
  EXPECT_EQ(error_of("ptp home zone=5mm\n"),
            "t.prog:1:10: found 'zone', expected an option of PTP: speed=N% and accel=N% (of the joints' limits)");
  EXPECT_EQ(error_of("lin home speed=5mm/s speed=6mm/s\n"), "t.prog:1:22: found 'speed', expected each option once per move");
  EXPECT_EQ(error_of("lin home speed 5mm/s\n"), "t.prog:1:16: found '5mm/s', expected '=' and a value after speed");
  EXPECT_EQ(error_of("lin home speed=\n"),
            "t.prog:1:16: found the end of the line, expected a value for speed (a number with its unit, a variable or '(')");
  EXPECT_EQ(error_of("lin home + wrist(z=1mm)\n"),
            "t.prog:1:12: found 'wrist', expected tool(...) or base(...) after '+': an offset in the tool's or the base's frame");
  EXPECT_EQ(error_of("lin home + tool(q=1mm)\n"), "t.prog:1:17: found 'q', expected a field of tool: x, y, z");
  EXPECT_EQ(error_of("ptp pose(x=1mm, y=2mm)\n"), "t.prog:1:5: found 'pose(...)', expected x, y and z in a pose (z is missing)");
  EXPECT_EQ(error_of("ptp pose(x=1mm, y=2mm, z=3mm, elbow=sideways)\n"),
            "t.prog:1:37: found 'sideways', expected elbow up or down (xArm), left or right (SCARA)");
  EXPECT_EQ(error_of("ptp joints(1deg, 2deg\n"),
            "t.prog:1:22: found the end of the line, expected ',' and another joint value, or ')'");
  EXPECT_EQ(error_of("circ a b\n"),
            "t.prog:1:8: found 'b', expected ',' and the CIRC's target after its via point (CIRC via, target)");
  EXPECT_EQ(error_of("wait 2 s\n"), "t.prog:1:8: found 's', expected the end of the line after WAIT time");
  EXPECT_EQ(error_of("wait 2sec\n"),
            "t.prog:1:7: found 'sec', expected a unit after the number: mm, cm, m, deg, rad, s, ms, %, mm/s, m/s, deg/s, "
            "rad/s, mm/s^2, m/s^2, deg/s^2, rad/s^2");
  EXPECT_EQ(error_of("loop 3\nend\n"), "t.prog:1:7: found the end of the line, expected TIMES after the count (LOOP 3 TIMES)");
  EXPECT_EQ(error_of("loop 3 times\n  wait 1s\n"),
            "t.prog:3:1: found the end of the file, expected END to close the LOOP at line 1");
  EXPECT_EQ(error_of("if 1 then\nelse\nelse\nend\n"),
            "t.prog:3:1: found 'else', expected a statement: PTP, LIN, CIRC, WAIT, GRIPPER, PRINT, IF, LOOP, WHILE, "
            "CALL, OVERRIDE, DEF or NAME = value");
  EXPECT_EQ(error_of("end\n"),
            "t.prog:1:1: found 'end', expected a statement: PTP, LIN, CIRC, WAIT, GRIPPER, PRINT, IF, LOOP, WHILE, "
            "CALL, OVERRIDE, DEF or NAME = value");
  EXPECT_EQ(error_of("def a()\nend\ndef a()\nend\n"), "t.prog:3:1: found 'a', expected each subroutine name once ('a' is defined at line 1)");
  EXPECT_EQ(error_of("def a(x, x)\nend\n"), "t.prog:1:10: found 'x', expected each parameter name once");
  EXPECT_EQ(error_of("loop 2 times\ndef a()\nend\nend\n"),
            "t.prog:2:1: found 'def', expected a statement (a DEF belongs outside any other block: END to close the "
            "LOOP at line 1 first)");
  EXPECT_EQ(error_of("lin = 3\n"),
            "t.prog:1:5: found '=', expected the LIN's target: a point name, pose(x=.., y=.., z=..) or joints(..)");
  EXPECT_EQ(error_of("n = 3 +\n"),
            "t.prog:1:8: found the end of the line, expected a value after '=' (a number with its unit, a variable or '(')");
  EXPECT_EQ(error_of("n = (3\n"), "t.prog:1:7: found the end of the line, expected ')' to close the '('");
  EXPECT_EQ(error_of("print \"open\n"), "t.prog:1:7: found '\"open', expected a closing '\"' on the same line");
  EXPECT_EQ(error_of("n = 3 $ 4\n"),
            "t.prog:1:7: found '$', expected a name, a number, a \"text\", an operator (+ - * / < <= > >= == !=) or ( ) , =");
  EXPECT_EQ(error_of("n = 12abc\n"),
            "t.prog:1:7: found 'abc', expected a unit after the number: mm, cm, m, deg, rad, s, ms, %, mm/s, m/s, deg/s, "
            "rad/s, mm/s^2, m/s^2, deg/s^2, rad/s^2");
  EXPECT_EQ(error_of("gripper\n"),
            "t.prog:1:8: found the end of the line, expected OPEN, CLOSE or how far closed (e.g. GRIPPER 40%) after "
            "GRIPPER (a number with its unit, a variable or '(')");
  EXPECT_EQ(error_of("call pick\n"),
            "t.prog:1:10: found the end of the line, expected '(' and the arguments after the subroutine's name (CALL "
            "name() for none)");
}

TEST(ProgramParser, DeepNestingIsRefusedNotACrash) {
  std::string deep = "n = " + std::string(200, '(') + "1" + std::string(200, ')') + "\n";
  EXPECT_EQ(error_of(deep), "t.prog:1:69: found '(', expected at most 64 parentheses, signs and NOTs inside one another");
  // 250,000 signs or NOTs: refused at the 65th, not parsed into a tree that deep.
  EXPECT_EQ(error_of("n = " + std::string(250'000, '-') + "1\n"),
            "t.prog:1:69: found '-', expected at most 64 parentheses, signs and NOTs inside one another");
  std::string nots = "n = ";
  for (int i = 0; i < 250'000; ++i) nots += "not ";
  EXPECT_EQ(error_of(nots + "1\n"),
            "t.prog:1:261: found 'not', expected at most 64 parentheses, signs and NOTs inside one another");
  std::string blocks;
  for (int i = 0; i < 40; ++i) blocks += "if 1\n";
  EXPECT_NE(error_of(blocks).find("at most 32 IF/LOOP/WHILE inside one another"), std::string::npos);
}

// A program saved with a UTF-8 byte-order mark reads as without it; errors keep their columns.
TEST(ProgramParser, AByteOrderMarkIsNotPartOfAProgramFile) {
  const auto path = std::filesystem::temp_directory_path() / ("armctl-bom-" + std::to_string(::getpid()) + ".prog");
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBFptp home\n";
  auto p = read_program_file(path);
  ASSERT_TRUE(p) << p.error().message;
  ASSERT_EQ(p->main.size(), 1u);
  EXPECT_EQ(p->main[0].target.point, "home");
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBFptp home zone=5mm\n";
  EXPECT_EQ(read_program_file(path).error().message,
            path.string() + error_of("ptp home zone=5mm\n").substr(std::string("t.prog").size()));
  std::filesystem::remove(path);
}

// A sum, product or AND chain of 250,000 terms crashed the CLI and the server's check
// endpoint (a stack overflow in the evaluator and in freeing the tree): it is refused at
// the operator past the limit, with its place.
TEST(ProgramParser, LongChainsAreRefusedAtTheOperatorPastTheLimit) {
  // Written as tightly as the language allows (a program is at most 1 MiB).
  for (const std::string op : {"+", "*"}) {
    std::string text = "n = 1";
    for (int i = 0; i < 250'000; ++i) text += op + "1";
    // "n = 1" then "op1" per term: the 1001st operator is at column 6 + 2 * 1000.
    EXPECT_EQ(error_of(text + "\n"), fmt::format("t.prog:1:2006: found '{}', expected at most 1000 operators in one "
                                                 "expression (split it: give parts of it to variables)",
                                                 op));
  }
  for (const std::string op : {"and", "or"}) {
    std::string text = "n = 1";
    for (int i = 0; i < 170'000; ++i) text += " " + op + " 1";
    // " op 1" per term: the 1001st operator is 1000 terms on from column 7.
    const std::size_t column = 7 + 1000 * (op.size() + 3);
    EXPECT_EQ(error_of(text + "\n"), fmt::format("t.prog:1:{}: found '{}', expected at most 1000 operators in one "
                                                 "expression (split it: give parts of it to variables)",
                                                 column, op));
  }
  // At the limit it parses.
  std::string at_limit = "n = 1";
  for (int i = 0; i < 1000; ++i) at_limit += " + 1";
  EXPECT_EQ(parsed(at_limit + "\n").main.size(), 1u);
}

}  // namespace
}  // namespace armctl::program
