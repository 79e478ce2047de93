// Test helpers: an emulated xArm on a SimClock with its output captured, hex helpers and
// the shared Robot Commands vectors.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/clock.hpp"
#include "devices/xarm_emulator/xarm_emulator.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::xarm::test {

inline std::vector<std::uint8_t> hex(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::istringstream in(text);
  std::string byte;
  while (in >> byte) out.push_back(static_cast<std::uint8_t>(std::stoul(byte, nullptr, 16)));
  return out;
}

inline std::string to_hex(const std::vector<std::uint8_t>& b) {
  return rc::to_hex(b);
}

// The vector named `name` from robot-commands.json (bytes as a vector).
inline std::vector<std::uint8_t> vector_bytes(const std::string& name) {
  static const nlohmann::json vectors = [] {
    std::ifstream in(std::string(ARMCTL_VECTORS_DIR) + "/robot-commands.json");
    return nlohmann::json::parse(in);
  }();
  for (const auto& v : vectors["vectors"])
    if (v["name"] == name) return hex(v["bytes"].get<std::string>());
  ADD_FAILURE() << "no vector named " << name;
  return {};
}

inline nlohmann::json malformed_vectors() {
  std::ifstream in(std::string(ARMCTL_VECTORS_DIR) + "/robot-commands.json");
  return nlohmann::json::parse(in)["malformed"];
}

// A fresh directory under the test's temp dir, removed at the end.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "armctl-board-XXXXXX").string();
    path_ = ::mkdtemp(tmpl.data()) ? std::filesystem::path(tmpl) : std::filesystem::path();
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

struct Emulated {
  explicit Emulated(XarmEmulatorOptions options = {})
      : emulator(clock, std::move(options), [this](const rc::Frame& f) { out.push_back(f); }) {}

  void send(const std::vector<std::uint8_t>& bytes) { emulator.receive(bytes); }
  void send(const rc::Request& request) {
    auto frame = rc::encode(request, rc::ServoRange{1, 6});
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    send(rc::encode_frame(*frame));
  }
  // Encodes for a board with servos 1..254, so the emulator (not the encoder) judges which
  // servos exist.
  void send_unchecked(const rc::Request& request) {
    auto frame = rc::encode(request, rc::ServoRange{1, 254});
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    send(rc::encode_frame(*frame));
  }
  // Sends a frame that the host library would refuse (bypasses validation).
  void send_raw(std::uint8_t cmd, std::vector<std::uint8_t> data) {
    send(rc::encode_frame(rc::Frame{cmd, std::move(data)}));
  }
  void advance_ms(int ms) {
    clock.advance(std::chrono::milliseconds(ms));
    emulator.poll();
  }
  std::vector<std::uint8_t> take_bytes() {
    std::vector<std::uint8_t> bytes;
    for (const auto& f : out) {
      auto b = rc::encode_frame(f);
      bytes.insert(bytes.end(), b.begin(), b.end());
    }
    out.clear();
    return bytes;
  }
  std::int16_t position(std::uint8_t servo) { return emulator.servos().position(servo); }
  rc_board::BoardStats stats() const { return emulator.board().stats(); }

  SimClock clock;
  std::vector<rc::Frame> out;
  XarmEmulator emulator;
};

}  // namespace armctl::xarm::test
