// Replays every transcript of ../shared/vectors/joint-bus.json byte-exactly against the
// portable JointController (its joint number taken from the transcript's select line).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

using testing::BusHarness;
using testing::EncoderDriver;

nlohmann::json load_vectors() {
  std::ifstream in(std::string(ARMCTL_VECTORS_DIR) + "/joint-bus.json");
  EXPECT_TRUE(in.good()) << "cannot open joint-bus.json in " << ARMCTL_VECTORS_DIR;
  return nlohmann::json::parse(in);
}

std::vector<std::uint8_t> hex_bytes(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::istringstream in(text);
  std::string token;
  while (in >> token) out.push_back(static_cast<std::uint8_t>(std::stoul(token, nullptr, 16)));
  return out;
}

// The state a transcript assumes before it starts, from its name ("... at <value>").
void apply_precondition(const std::string& name, JointController& joint, EncoderDriver& encoder) {
  std::smatch m;
  if (!std::regex_search(name, m, std::regex(R"(^(get_position|get_target) joint \d at (-?\d+))"))) return;
  const int value = std::stoi(m[2]);
  if (m[1] == "get_position") {
    encoder.move(joint, value);
  } else {
    ASSERT_EQ(joint.execute(cmd_drive_to, static_cast<int16_t>(value)).status,
              success_status(cmd_drive_to));
  }
}

TEST(JointBusVectors, EveryTranscriptReplaysByteExactly) {
  const nlohmann::json vectors = load_vectors();
  ASSERT_TRUE(vectors.contains("transcripts"));
  int replayed = 0;
  for (const auto& transcript : vectors["transcripts"]) {
    const std::string name = transcript["name"];
    SCOPED_TRACE(name);
    const auto& steps = transcript["steps"];
    ASSERT_FALSE(steps.empty());
    // First step: "select N high" names the joint.
    std::smatch m;
    const std::string first = steps[0][1];
    ASSERT_TRUE(std::regex_match(first, m, std::regex(R"(select (\d) high)")));
    const int joint_number = std::stoi(m[1]);

    JointController joint;
    ASSERT_TRUE(joint.begin(static_cast<uint8_t>(joint_number), default_tuning(), 9600));
    joint.init_encoder(false, false);
    EncoderDriver encoder;
    apply_precondition(name, joint, encoder);
    BusHarness bus(joint, 9600, 0xFFFFF000u);  // start near the uint32 wrap on purpose

    std::vector<std::uint8_t> sent_by_joint;
    for (const auto& step : steps) {
      const std::string who = step[0];
      const std::string what = step[1];
      if (who == "master") {
        if (std::regex_match(what, m, std::regex(R"(select (\d) (high|low))"))) {
          ASSERT_EQ(std::stoi(m[1]), joint_number);
          // A master waits for the joint's bytes before the next step: nothing pending.
          ASSERT_TRUE(bus.drain().empty());
          bus.select(m[2] == "high");
        } else {
          for (std::uint8_t b : hex_bytes(what)) bus.send(b);
        }
      } else {
        ASSERT_EQ(who, "joint");
        EXPECT_EQ(bus.drain(), hex_bytes(what));
      }
    }
    EXPECT_TRUE(bus.drain().empty());
    EXPECT_FALSE(joint.tx_enabled());
    EXPECT_EQ(joint.transaction().state(), BusTransaction::State::idle);

    // Transcripts that note "unchanged" must leave the state as begin() made it.
    const std::string note = transcript.value("note", "");
    if (note.find("unchanged") != std::string::npos) {
      EXPECT_TRUE(joint.loop_enabled());
      EXPECT_EQ(joint.speed_percent(), 100);
      EXPECT_EQ(joint.zone(), 0);
      EXPECT_EQ(joint.target(), 0);
    }
    ++replayed;
  }
  EXPECT_EQ(replayed, 17);
}

// The master-side case that has a joint-side half: drive_dist past int16 on 32767.
TEST(JointBusVectors, DriveDistPastInt16IsBadDataAndKeepsTarget) {
  JointController joint;
  ASSERT_TRUE(joint.begin(2, default_tuning(), 9600));
  BusHarness bus(joint);
  EXPECT_EQ(bus.transact(cmd_drive_to, int16_t{32767}).status_word(), 220);
  const auto e = bus.transact(cmd_drive_dist, int16_t{1});
  EXPECT_EQ(e.status_word(), status_bad_data);
  EXPECT_EQ(joint.target(), 32767);
}

}  // namespace
}  // namespace armctl::joint_bus
