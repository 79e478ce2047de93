// A fake JointBusLink that replays one transcript from joint-bus.json byte-exactly: joint
// bytes become readable only once every master step before them has happened, and every
// master action (select edges, written bytes) is logged in the transcript's own notation
// so a test can compare the two. Time is simulated: a read with nothing to read jumps the
// clock to the deadline.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "core/clock.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::test {

struct Step {
  bool master;       // true: the master does it; false: the joint sends it
  std::string text;  // "select 3 high" or hex bytes "03 00"
};

inline std::vector<std::uint8_t> parse_hex(const std::string& text) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i < text.size(); i += 3) {
    out.push_back(static_cast<std::uint8_t>(std::stoi(text.substr(i, 2), nullptr, 16)));
  }
  return out;
}

inline std::string to_hex(const std::vector<std::uint8_t>& bytes) {
  std::string s;
  for (std::uint8_t b : bytes) s += fmt::format("{}{:02X}", s.empty() ? "" : " ", b);
  return s;
}

class ScriptedLink final : public transport::JointBusLink {
 public:
  ScriptedLink(std::vector<Step> steps, std::uint32_t baud = 9600, int joints = 7)
      : steps_(std::move(steps)), baud_(baud), joints_(joints) {}

  int joint_count() const override { return joints_; }
  void set_select(int joint, bool high) override {
    end_write();
    log_.push_back(fmt::format("select {} {}", joint, high ? "high" : "low"));
  }
  void write(std::span<const std::uint8_t> bytes) override {
    pending_write_.insert(pending_write_.end(), bytes.begin(), bytes.end());
  }
  void flush() override { end_write(); }
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override {
    end_write();
    release_joint_bytes();
    if (rx_.empty()) {
      clock_.advance_to(deadline);
      return std::nullopt;
    }
    const std::uint8_t b = rx_.front();
    rx_.pop_front();
    return b;
  }
  std::size_t drain() override {
    end_write();
    release_joint_bytes();
    const std::size_t n = rx_.size();
    rx_.clear();
    return n;
  }
  const Clock& clock() const override { return clock_; }
  std::uint32_t baud() const override { return baud_; }

  const std::vector<std::string>& master_log() const { return log_; }
  std::vector<std::string> expected_master_log() const {
    std::vector<std::string> out;
    for (const Step& s : steps_) {
      if (s.master) out.push_back(s.text);
    }
    return out;
  }
  bool all_joint_bytes_sent() const { return next_step_ == steps_.size() && rx_.empty(); }
  SimClock& sim_clock() { return clock_; }

 private:
  void end_write() {
    if (pending_write_.empty()) return;
    log_.push_back(to_hex(pending_write_));
    pending_write_.clear();
  }
  // Moves joint steps into rx_ while the master has done exactly what preceded them.
  void release_joint_bytes() {
    while (next_step_ < steps_.size()) {
      const Step& s = steps_[next_step_];
      if (s.master) {
        if (master_seen_ >= log_.size() || log_[master_seen_] != s.text) return;
        ++master_seen_;
      } else {
        for (std::uint8_t b : parse_hex(s.text)) rx_.push_back(b);
      }
      ++next_step_;
    }
  }

  std::vector<Step> steps_;
  std::size_t next_step_ = 0;
  std::size_t master_seen_ = 0;
  std::vector<std::string> log_;
  std::vector<std::uint8_t> pending_write_;
  std::deque<std::uint8_t> rx_;
  SimClock clock_;
  std::uint32_t baud_;
  int joints_;
};

}  // namespace armctl::test
