// The master against every transcript in joint-bus.json, byte-exactly, through the typed
// API; plus the master-side and legacy-dialect vectors.
#include <gtest/gtest.h>

#include "devices/joint_bus/bus_master.hpp"
#include "portable/joint_bus_codes.hpp"
#include "scripted_link.hpp"
#include "vectors.hpp"

namespace armctl::test {
namespace {

using joint_bus::BusMaster;
using joint_bus::Dialect;
using joint_bus::FailureKind;
using joint_bus::MasterOptions;

struct Call {
  bool ok = false;
  std::optional<std::int16_t> value;  // RESPONSE-derived value, when the command has one
  std::optional<joint_bus::JointFailure> failure;
  std::string message;  // the error's, when it failed
};

template <typename T>
Call to_call(const Result<T>& r) {
  Call c;
  c.ok = r.ok();
  if (!r.ok()) {
    c.failure = *joint_bus::joint_failure(r.error());
    c.message = r.error().message;
  } else if constexpr (std::is_same_v<T, std::int16_t>) {
    c.value = *r;
  } else if constexpr (std::is_same_v<T, bool>) {
    c.value = *r ? 1 : 0;
  }
  return c;
}

// Calls the typed API that corresponds to a command word (raw transact for unknown codes).
Call call_typed(BusMaster& m, int joint, std::int16_t command, std::optional<std::int16_t> data) {
  using namespace joint_bus;
  switch (command) {
    case cmd_ping: return to_call(m.ping(joint, *data));
    case cmd_home: return to_call(m.home(joint));
    case cmd_set_pid_state:
      // the typed API only sends 0/1: other values go through the raw path
      if (*data == 0 || *data == 1) return to_call(m.set_pid_state(joint, *data == 1));
      break;
    case cmd_get_position: return to_call(m.get_position(joint));
    case cmd_get_target: return to_call(m.get_target(joint));
    case cmd_get_joint_number: return to_call(m.get_joint_number(joint));
    case cmd_drive_dist: return to_call(m.drive_dist(joint, *data));
    case cmd_drive_dist_max: return to_call(m.drive_dist_max(joint, *data));
    case cmd_drive_to: return to_call(m.drive_to(joint, *data));
    case cmd_set_speed: return to_call(m.set_speed(joint, *data));
    case cmd_set_zone: return to_call(m.set_zone(joint, *data));
    case cmd_check_target_reached: return to_call(m.check_target_reached(joint));
    default: break;
  }
  return to_call(m.transact(joint, command, data));
}

struct Parsed {
  int joint;
  std::int16_t command;
  std::optional<std::int16_t> data;
  std::optional<std::int16_t> response;
  std::int16_t status;
};

Parsed parse(const Transcript& t) {
  Parsed p{};
  p.joint = t.steps.at(0).text.at(7) - '0';  // "select N high"
  const auto cmd = parse_hex(t.steps.at(2).text);
  p.command = joint_bus::word_from(cmd.at(0), cmd.at(1));
  if (cmd.size() == 4) p.data = joint_bus::word_from(cmd.at(2), cmd.at(3));
  if (!t.steps.at(3).master) {
    const auto r = parse_hex(t.steps.at(3).text);
    p.response = joint_bus::word_from(r.at(0), r.at(1));
  }
  const auto s = parse_hex(t.steps.back().text);
  p.status = joint_bus::word_from(s.at(0), s.at(1));
  return p;
}

class TranscriptTest : public ::testing::TestWithParam<Transcript> {};

TEST_P(TranscriptTest, MasterReplaysByteExactlyAndReportsTheOutcome) {
  const Transcript& t = GetParam();
  const Parsed p = parse(t);
  ScriptedLink link(t.steps);
  BusMaster master(link);
  const Call c = call_typed(master, p.joint, p.command, p.data);

  EXPECT_EQ(link.master_log(), link.expected_master_log()) << t.name;
  EXPECT_TRUE(link.all_joint_bytes_sent()) << t.name;
  if (p.status == joint_bus::success_status(p.command)) {
    ASSERT_TRUE(c.ok) << t.name << ": " << c.message;
    if (p.response && p.command != joint_bus::cmd_ping) {
      EXPECT_EQ(c.value, p.response) << t.name;
    }
  } else {
    ASSERT_FALSE(c.ok) << t.name;
    EXPECT_EQ(c.failure->code(), p.status) << t.name;
    EXPECT_EQ(c.failure->status_word, p.status) << t.name;
    EXPECT_TRUE(c.failure->command_sent);
  }
}

INSTANTIATE_TEST_SUITE_P(JointBusJson, TranscriptTest, ::testing::ValuesIn(load_transcripts()),
                         [](const auto& param_info) { return "transcript_" + std::to_string(param_info.index); });

TEST(MasterSideVectors, VectorsFileHasTheCasesTheseTestsCover) {
  const auto v = load_joint_bus_vectors();
  ASSERT_EQ(v.at("master_side").size(), 4u);
  EXPECT_NE(v.at("master_side")[0].at("expect").get<std::string>().find("910"), std::string::npos);
  EXPECT_NE(v.at("master_side")[1].at("expect").get<std::string>().find("920"), std::string::npos);
  EXPECT_NE(v.at("master_side")[2].at("expect").get<std::string>().find("990"), std::string::npos);
  EXPECT_NE(v.at("master_side")[3].at("expect").get<std::string>().find("940"), std::string::npos);
}

// "joint 3 selected, READY word is 05 00": 910, select dropped, no COMMAND sent.
TEST(MasterSideVectors, WrongReadyDropsSelectAndSendsNoCommand) {
  ScriptedLink link({{true, "select 3 high"}, {false, "05 00"}, {true, "select 3 low"}});
  BusMaster master(link);
  auto r = master.get_position(3);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 910);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::wrong_joint);
  EXPECT_FALSE(joint_bus::joint_failure(r.error())->command_sent);
  EXPECT_EQ(link.master_log(), (std::vector<std::string>{"select 3 high", "select 3 low"}));
}

// "ping joint 2 with 1234, RESPONSE is D3 04": 920.
TEST(MasterSideVectors, PingBadEcho) {
  ScriptedLink link({{true, "select 2 high"}, {false, "02 00"}, {true, "00 00 D2 04"},
                     {false, "D3 04"}, {true, "select 2 low"}, {false, "64 00"}});
  BusMaster master(link);
  auto r = master.ping(2, 1234);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 920);
  EXPECT_EQ(link.master_log(), link.expected_master_log());
}

// "no READY within the timeout": 990 for that joint, bounded wait.
TEST(MasterSideVectors, NoReadyIsNoAnswerWithinTheBaudDerivedTimeout) {
  ScriptedLink link({{true, "select 6 high"}, {true, "select 6 low"}});
  BusMaster master(link);
  const TimePoint start = link.clock().now();
  auto r = master.get_target(6);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 990);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->stage, joint_bus::Stage::ready);
  EXPECT_FALSE(joint_bus::joint_failure(r.error())->command_sent);
  EXPECT_EQ(link.master_log(), link.expected_master_log());
  // READY timeout + a quiet period, both one word timeout long.
  EXPECT_EQ(link.clock().now() - start, 2 * master.options().timing.word_timeout(9600));
}

// "drive_dist of +1 on a target of 32767": the joint answers 940.
TEST(MasterSideVectors, DriveDistOverflowIsBadData) {
  ScriptedLink link({{true, "select 1 high"}, {false, "01 00"}, {true, "0A 00 01 00"},
                     {true, "select 1 low"}, {false, "AC 03"}});
  BusMaster master(link);
  auto r = master.drive_dist(1, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->status_word, 940);
}

TEST(MasterStatus, StatusThatIsNeitherSuccessNorErrorIsAProtocolError) {
  // 170 is get_target's success code: not an answer to get_position.
  ScriptedLink link({{true, "select 4 high"}, {false, "04 00"}, {true, "06 00"}, {false, "D4 FE"},
                     {true, "select 4 low"}, {false, "AA 00"}});
  BusMaster master(link);
  auto r = master.get_position(4);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::bad_status);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->status_word, 170);
  EXPECT_EQ(r.error().kind, ErrorKind::protocol);
}

TEST(MasterStatus, MissingStatusIsNoAnswerWithCommandSent) {
  ScriptedLink link({{true, "select 1 high"}, {false, "01 00"}, {true, "0C 00 64 00"},
                     {true, "select 1 low"}, {false, "C8"}});  // half a STATUS
  BusMaster master(link);
  auto r = master.drive_to(1, 100);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 990);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->stage, joint_bus::Stage::status);
  EXPECT_TRUE(joint_bus::joint_failure(r.error())->command_sent);
}

TEST(MasterStatus, MissingResponseIsNoAnswerAndNothingIsMadeUp) {
  ScriptedLink link({{true, "select 4 high"}, {false, "04 00"}, {true, "06 00"}, {false, "D4"},
                     {true, "select 4 low"}});
  BusMaster master(link);
  auto r = master.get_position(4);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 990);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->stage, joint_bus::Stage::response);
  EXPECT_EQ(link.master_log(), link.expected_master_log());
}

TEST(MasterStatus, ReachedAnswerOtherThanZeroOrOneIsRefused) {
  ScriptedLink link({{true, "select 3 high"}, {false, "03 00"}, {true, "14 00"}, {false, "02 00"},
                     {true, "select 3 low"}, {false, "2C 01"}});
  BusMaster master(link);
  auto r = master.check_target_reached(3);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::bad_status);
}

TEST(MasterArguments, JointOutsideTheBusIsRefusedBeforeAnythingIsSent) {
  ScriptedLink link({});
  BusMaster master(link);
  for (int j : {0, 8, -1}) {
    auto r = master.home(j);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::invalid_argument);
  }
  EXPECT_TRUE(link.master_log().empty());
}

// Legacy dialect: STATUS = command code on success, 93 unknown, 94 bad data.
std::vector<Step> with_status(const Transcript& t, const std::string& status) {
  std::vector<Step> steps = t.steps;
  steps.back().text = status;
  return steps;
}

const Transcript& transcript_named(const std::string& name) {
  static const std::vector<Transcript> all = load_transcripts();
  for (const auto& t : all) {
    if (t.name == name) return t;
  }
  throw std::runtime_error("no transcript " + name);
}

TEST(LegacyDialect, VectorStatusesAreUnderstoodOnlyInTheLegacyDialect) {
  const auto legacy = load_joint_bus_vectors().at("legacy_dialect");
  ASSERT_EQ(legacy.size(), 4u);
  struct Case {
    std::string transcript;
    FailureKind failure_or_ok;
    bool ok;
  };
  const Case cases[] = {
      {"ping joint 3 with 1234", FailureKind::bad_status, true},
      {"get_position joint 4 at -300", FailureKind::bad_status, true},
      {"unknown command 99 on joint 3", FailureKind::unknown_command, false},
      {"set_speed joint 1 to 150: bad data", FailureKind::bad_data, false},
  };
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string status = legacy[i].at("status").get<std::string>();
    const Transcript& t = transcript_named(cases[i].transcript);
    const Parsed p = parse(t);
    for (Dialect d : {Dialect::legacy, Dialect::standard}) {
      ScriptedLink link(with_status(t, status));
      MasterOptions o;
      o.dialect = d;
      BusMaster master(link, o);
      const Call c = call_typed(master, p.joint, p.command, p.data);
      SCOPED_TRACE(legacy[i].at("case").get<std::string>() + " in " + joint_bus::to_string(d));
      if (d == Dialect::legacy) {
        EXPECT_EQ(c.ok, cases[i].ok);
        if (!c.ok) {
          EXPECT_EQ(c.failure->kind, cases[i].failure_or_ok);
          EXPECT_EQ(c.failure->status_word, joint_bus::word_from(parse_hex(status).at(0), parse_hex(status).at(1)));
        }
      } else {
        // A legacy STATUS means nothing in the standard dialect: never a success.
        ASSERT_FALSE(c.ok);
        EXPECT_EQ(c.failure->kind, FailureKind::bad_status);
      }
    }
  }
}

TEST(LegacyDialect, StandardStatusIsNotSuccessInLegacyDialect) {
  const Transcript& t = transcript_named("home joint 1");
  ScriptedLink link(t.steps);
  MasterOptions o;
  o.dialect = Dialect::legacy;
  BusMaster master(link, o);
  auto r = master.home(1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::bad_status);
}

}  // namespace
}  // namespace armctl::test

namespace armctl::test {
namespace {

// Unknown command codes have no success STATUS in either dialect (issue 14, section 6).
TEST(UnknownCommands, LegacyNinetyThreeAnsweredWithNinetyThreeIsUnknownNotSuccess) {
  EXPECT_EQ(joint_bus::interpret_status(Dialect::legacy, 93, 93), joint_bus::StatusMeaning::unknown_command);
  EXPECT_EQ(joint_bus::interpret_status(Dialect::legacy, 94, 94), joint_bus::StatusMeaning::bad_data);
  EXPECT_EQ(joint_bus::interpret_status(Dialect::legacy, 12, 12), joint_bus::StatusMeaning::success);
  EXPECT_EQ(joint_bus::interpret_status(Dialect::legacy, 40, 40), joint_bus::StatusMeaning::success);
  EXPECT_EQ(joint_bus::interpret_status(Dialect::standard, 99, 1090), joint_bus::StatusMeaning::unexpected);
  EXPECT_FALSE(joint_bus::success_status(Dialect::standard, 99).has_value());
  EXPECT_FALSE(joint_bus::success_status(Dialect::legacy, 93).has_value());
  EXPECT_EQ(joint_bus::success_status(Dialect::standard, 41), 510);

  ScriptedLink link({{true, "select 1 high"}, {false, "01 00"}, {true, "5D 00"}, {true, "select 1 low"},
                     {false, "5D 00"}});
  MasterOptions o;
  o.dialect = Dialect::legacy;
  BusMaster master(link, o);
  auto r = master.transact(1, 93, std::nullopt);
  ASSERT_FALSE(r.ok()) << "STATUS 93 after command 93 read as success";
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::unknown_command);
}

TEST(UnknownCommands, StandardUnknownCodeAnsweredOddlyIsNotCalledSuccess1090) {
  ScriptedLink link({{true, "select 1 high"}, {false, "01 00"}, {true, "63 00"}, {true, "select 1 low"},
                     {false, "42 04"}});  // STATUS 1090 = 100 + 10 x 99
  BusMaster master(link);
  auto r = master.transact(1, 99, std::nullopt);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::bad_status);
  EXPECT_EQ(r.error().message.find("success (1090)"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("no joint knows"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("930"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace armctl::test

namespace armctl::test {
namespace {

TEST(UnknownCommands, TheOriginalFirmwareAnswersReadDiagnosticAsUnknownWithoutAResponse) {
  // Original firmware: no RESPONSE for a code it does not know, STATUS 93 after select falls.
  ScriptedLink link({{true, "select 4 high"}, {false, "04 00"}, {true, "28 00 00 00"}, {true, "select 4 low"},
                     {false, "5D 00"}});
  MasterOptions o;
  o.dialect = Dialect::legacy;
  BusMaster master(link, o);
  auto r = master.read_diagnostics(4);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::unknown_command);
  EXPECT_NE(r.error().message.find("does not know read_diagnostic"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace armctl::test
