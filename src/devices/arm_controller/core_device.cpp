#include "devices/arm_controller/core_device.hpp"

#include <algorithm>
#include <array>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/joint_diagnostics.hpp"
#include "protocol/robot_commands/command_codes.hpp"
#include "protocol/robot_commands/joint_faults.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::arm_controller {

namespace {

using namespace std::chrono_literals;

// Longest the loop waits between transactions before polling the core again: due commands
// are then late by at most this (a Mega main-loop pass is ~12 µs; the host's loop is also
// the runner's, which looks at the host between steps).
constexpr Duration kPass = 100us;
// At start, how long the first sweep of polls may take before serving anyway (joints
// that do not answer are retried by polling, as on the Mega).
constexpr Duration kFirstSweep = 2s;

// The group memory's file, in the state dir (created if need be).
std::optional<std::filesystem::path> memory_path(const CoreDeviceOptions& options) {
  if (!options.state_dir) return std::nullopt;
  std::error_code ec;
  std::filesystem::create_directories(*options.state_dir, ec);
  if (ec)
    throw ArmctlError(ErrorKind::io, fmt::format("state dir {}: cannot create it: {}",
                                                 options.state_dir->string(), ec.message()));
  return *options.state_dir / CoreDevice::memory_file;
}

// What the earlier implementation kept in the state dir, while the core has no memory there
// yet (once it has, the next start must not import again). Read before the memory file is
// created: a settings file it cannot read stops the start with nothing created.
std::optional<DaemonState> state_to_import(const CoreDeviceOptions& options, const ControllerConfig& config) {
  std::error_code ec;
  if (!options.state_dir || std::filesystem::exists(*options.state_dir / CoreDevice::memory_file, ec))
    return std::nullopt;
  return find_daemon_state(*options.state_dir, config);
}

std::vector<controller::JointSetup> checked_setups(const ControllerConfig& config,
                                                   const transport::JointBusLink& link) {
  for (const auto& j : config.joints)
    if (j.number > link.joint_count())
      throw ArmctlError(ErrorKind::invalid_config,
                        fmt::format("arm config joint {} ({}) has no select line: the bus has joints 1..{}",
                                    int(j.number), j.name, link.joint_count()));
  return core_joint_setups(config);
}

}  // namespace

void CoreDevice::Upstream::send_frame(std::uint8_t command, const std::uint8_t* data, std::uint8_t length) {
  const rc::Frame frame{command, std::vector<std::uint8_t>(data, data + length)};
  watch_(frame);
  out_(frame);
}

CoreDevice::CoreDevice(transport::JointBusLink& link, ControllerConfig config, CoreDeviceOptions options,
                       Output output)
    : link_(link),
      config_(std::move(config)),
      options_(std::move(options)),
      joints_(checked_setups(config_, link)),
      port_(link),
      upstream_(std::move(output), [this](const rc::Frame& f) { watch(f); }),
      to_import_(state_to_import(options_, config_)),
      memory_(memory_path(options_), memory_size),
      directory_(group_entries),
      seen_(joints_.size()) {
  core_.begin(joints_.data(), static_cast<std::uint8_t>(joints_.size()), &port_, &upstream_, link_.baud(), now_us(),
              &memory_, directory_.data(), group_entries);
  const TimePoint give_up = clock().now() + kFirstSweep;
  while (core_.stats().sweeps == 0 && clock().now() < give_up) step(give_up);
  for (std::size_t i = 0; i < joints_.size(); ++i) seen_[i] = Seen::of(core_.joint_state(joints_[i].number));
  if (options_.link_losses) losses_seen_ = options_.link_losses();
  started_ = true;
  // A state dir the daemon's earlier implementation kept: its groups and settings, once.
  if (to_import_) {
    for (const std::string& line : import_daemon_state(*to_import_, config_, *this)) log(line);
    to_import_.reset();
  }
}

std::uint32_t CoreDevice::now_us() const {
  // The core's clock is a wrapping microsecond counter; it compares by difference.
  return static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(clock().now().time_since_epoch()).count());
}

void CoreDevice::receive(std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) {
    const std::uint16_t torn = reader_.torn_frames();
    if (reader_.on_byte(b, now_us()))
      take(rc::Frame{reader_.command(),
                     std::vector<std::uint8_t>(reader_.data(), reader_.data() + reader_.data_length())});
    if (reader_.torn_frames() != torn) log("a partial frame was dropped (its bytes stopped for over 50 ms): ignored");
  }
}

void CoreDevice::handle(const rc::Frame& frame) {
  // What the wire could carry: a longer frame never reaches a board.
  if (frame.data.size() + 2 > controller::RcFrameReader::max_length) return;
  take(frame);
}

void CoreDevice::take(const rc::Frame& frame) {
  const controller::CoreStats before = core_.stats();
  core_.on_frame(frame.cmd, frame.data.data(), static_cast<std::uint8_t>(frame.data.size()), now_us());
  if (options_.log) explain(frame, before);
}

void CoreDevice::explain(const rc::Frame& frame, const controller::CoreStats& before) const {
  // The core only counts; the log says which frame and, where the host's codec can tell,
  // why (a move naming a joint not answering; a frame malformed as the spec reads it).
  const controller::CoreStats& after = core_.stats();
  if (after.refused_moves == before.refused_moves && after.download_too_big == before.download_too_big &&
      after.download_rejected == before.download_rejected && after.ignored_frames == before.ignored_frames)
    return;  // taken: nothing to say
  const auto command = rc::command_from_byte(frame.cmd);
  const std::string name = command ? rc::command_name(*command) : fmt::format("CMD {}", frame.cmd);
  auto request = rc::decode_request(frame, rc::ServoRange{0, 255});
  if (after.refused_moves != before.refused_moves) {
    std::string joints;
    if (request)
      if (const auto* move = std::get_if<rc::MultiServoMove>(&*request))
        for (const auto& t : move->targets)
          if (t.position && !core_.joint_state(t.servo).answering)
            joints += fmt::format("{}joint {} ({})", joints.empty() ? "" : ", ", t.servo,
                                  config_.joint(t.servo) ? config_.joint(t.servo)->name : "?");
    log(fmt::format("{} refused: {} not answering; no joint moved", name,
                    joints.empty() ? "a named joint is" : joints + (joints.find(',') == std::string::npos ? " is" : " are")));
  } else if (after.download_too_big != before.download_too_big) {
    log(fmt::format("{}: the group does not fit the group memory (or no free directory entry): refused; "
                    "erase groups to make room",
                    name));
  } else if (after.download_rejected != before.download_rejected) {
    log(fmt::format("{}: inconsistent with the download in progress: download abandoned; stored group unchanged", name));
  } else if (after.ignored_frames != before.ignored_frames) {
    log(request ? fmt::format("{} ignored: a servo that is not a joint, a position outside its limits, or a "
                              "request the board cannot take now",
                              name)
                : fmt::format("{} ignored: {}", name, request.error().message));
  }
}

void CoreDevice::step(TimePoint limit) {
  if (options_.link_losses && options_.link_losses() != losses_seen_) {
    losses_seen_ = options_.link_losses();
    core_.link_lost(now_us());
    log("joint bus link lost: playback and queued commands ended; joints count as not answering until polled again");
  }
  core_.set_battery_millivolts(options_.supply_millivolts ? options_.supply_millivolts() : config_.supply_millivolts);
  core_.flush_group_writes();  // a file takes every byte at once (FileGroupMemory)
  core_.poll(now_us());
  note_changes();
  // Mid-transaction the next event is a byte (or the master's timeout, several words away):
  // wait up to a word for it. Between transactions the core starts the next one at its next
  // poll, or waits for a due command or the quiet time after a failure: look again soon.
  const TimePoint now = clock().now();
  const Duration wait = core_.master().busy() ? std::chrono::microseconds(core_.master().word_time_us()) : kPass;
  const TimePoint deadline = std::min(limit, now + wait);
  if (deadline <= now) return;
  if (auto b = link_.read_byte(deadline)) core_.on_bus_byte(*b, now_us());
}

void CoreDevice::run_until(TimePoint t) {
  while (clock().now() < t) step(t);
}

void CoreDevice::note_changes() {
  // Before the first sweep is done the start-up log says where every joint is.
  if (!options_.log || !started_) return;
  if (core_.stats().actions_skipped != actions_skipped_seen_) {
    actions_skipped_seen_ = core_.stats().actions_skipped;
    log("GroupRun: an action was skipped (a joint it names is not answering, or its target is outside the joint's "
        "limits now); the run goes on");
  }
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const int n = joints_[i].number;
    const std::string& name = config_.joints[i].name;
    const controller::JointState& s = core_.joint_state(joints_[i].number);
    Seen& seen = seen_[i];
    if (s.answering != seen.answering)
      log(s.answering ? fmt::format("joint {} {}: answering again", n, name)
                      : fmt::format("joint {} {}: not answering (status {})", n, name, s.last_fault));
    if (s.following_lost != seen.following_lost)
      log(fmt::format("joint {} {}: stopped following its plan; its faults are read", n, name));
    // Once a read completes, and again when a later read finds other faults (a runaway
    // shows 100-150 ms after the joint leaves its plan).
    if (s.diagnostics_read && (!seen.diagnostics_read || s.diagnostics[0] != seen.faults)) {
      std::array<std::uint16_t, joint_bus::diagnostic_count> words{};
      std::copy_n(s.diagnostics, words.size(), words.begin());
      log(fmt::format("joint {} {}: {}{}", n, name, joint_bus::describe(joint_bus::diagnostics_from_words(words)),
                      words[0] != 0 ? "; fix the cause, then 'armctl arm clear-faults' (JointFaultClear)" : ""));
    }
    seen = Seen::of(s);
  }
}

void CoreDevice::watch(const rc::Frame& frame) const {
  if (frame.cmd != rc::kJointFaultClearCmd || !options_.log) return;
  auto reply = rc::decode_joint_fault_clear_reply(frame);
  if (!reply) return;
  const auto* joint = config_.joint(reply->servo);
  const std::string who = fmt::format("joint {} ({})", reply->servo, joint ? joint->name : "?");
  log(reply->cleared() ? who + ": faults cleared; it holds where it is until a move names it"
                       : fmt::format("{}: clear_faults answered STATUS {}", who, reply->status));
}

void CoreDevice::log(const std::string& line) const {
  if (options_.log) options_.log(line);
}

}  // namespace armctl::arm_controller
