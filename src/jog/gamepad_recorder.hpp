// Records what a gamepad source hands over, in the format GamepadReplay plays
// (jog/gamepad_replay.hpp): `armctl jog --gamepad --record-gamepad FILE` makes the
// recordings that tests and demos replay. Time 0 is the first poll, as in a replay; the
// pad's description is the first one opened (a different pad plugged in later is recorded
// as the same pad coming back).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "jog/gamepad_replay.hpp"
#include "jog/gamepad_source.hpp"

namespace armctl::jog {

class GamepadRecorder final : public GamepadSource {
 public:
  explicit GamepadRecorder(std::unique_ptr<GamepadSource> source) : source_(std::move(source)) {}
  PadPoll poll(TimePoint now) override;
  std::string description() const override { return source_->description(); }

  // What was recorded, or nothing when no pad was ever opened.
  std::optional<PadRecording> recording() const;
  // Writes it to `path` atomically. Errors: no pad was ever opened (invalid_argument), the
  // file's (io).
  Status save(const std::filesystem::path& path) const;

 private:
  std::unique_ptr<GamepadSource> source_;
  std::optional<TimePoint> start_;
  PadRecording recording_;
  bool opened_ = false;
};

}  // namespace armctl::jog
