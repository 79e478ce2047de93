#include "jog/gamepad_recorder.hpp"

#include <cstdint>
#include <span>

#include "core/atomic_file.hpp"
#include "core/printable.hpp"

namespace armctl::jog {

PadPoll GamepadRecorder::poll(TimePoint now) {
  PadPoll p = source_->poll(now);
  if (!start_) start_ = now;
  const double t = std::chrono::duration<double>(now - *start_).count();
  using Kind = PadRecordingLine::Kind;
  if (p.connected) {
    if (!opened_) recording_.pad = *p.connected;
    else recording_.lines.push_back({Kind::plugged, t, 0, 0, 0});
    opened_ = true;
  }
  // Events are stamped with the poll that read them: a replay hands them over at that poll.
  if (opened_)
    for (const PadEvent& e : p.events)
      recording_.lines.push_back({Kind::event, std::chrono::duration<double>(e.time - *start_).count(), e.type,
                                  e.code, e.value});
  if (p.unplugged && opened_) recording_.lines.push_back({Kind::unplugged, t, 0, 0, 0});
  return p;
}

std::optional<PadRecording> GamepadRecorder::recording() const {
  if (!opened_) return std::nullopt;
  return recording_;
}

Status GamepadRecorder::save(const std::filesystem::path& path) const {
  if (!opened_)
    return Error{ErrorKind::invalid_argument,
                 "no gamepad was opened: nothing to record in " + printable(path.string())};
  const std::string text = format_pad_recording(recording_);
  return write_file_atomically(
      path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace armctl::jog
