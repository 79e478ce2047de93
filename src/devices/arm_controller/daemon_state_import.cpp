#include "devices/arm_controller/daemon_state_import.hpp"

#include <deque>
#include <optional>

#include <fmt/core.h>

#include "devices/arm_controller/core_device.hpp"
#include "devices/rc_board/group_store.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::arm_controller {

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// The SDK's link to the device in this process: a request goes to the core, the device runs
// while the SDK waits for the reply.
class CoreLink final : public robot_commands::RcLink {
 public:
  explicit CoreLink(CoreDevice& device) : device_(device) {}
  void deliver(const rc::Frame& f) { inbox_.push_back(f); }
  void send(const rc::Frame& frame) override { device_.handle(frame); }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    while (inbox_.empty()) {
      if (device_.clock().now() >= deadline) return std::nullopt;
      device_.step(deadline);
    }
    rc::Frame f = inbox_.front();
    inbox_.pop_front();
    return f;
  }
  const Clock& clock() const override { return device_.clock(); }
  std::string describe() const override { return "the core, importing"; }

 private:
  CoreDevice& device_;
  std::deque<rc::Frame> inbox_;
};

ControllerSettings default_settings(const ControllerConfig& config) {
  ControllerSettings s;
  for (const auto& j : config.joints) s.joints[j.number].limits.servo = j.number;
  s.info_joint = config.joints.front().number;
  return s;
}

}  // namespace

std::optional<DaemonState> find_daemon_state(const fs::path& state_dir, const ControllerConfig& config) {
  std::error_code ec;
  bool found = fs::exists(settings_path(state_dir), ec);
  for (int g = 0; g < static_cast<int>(rc_board::kGroupCount) && !found; ++g)
    found = fs::exists(state_dir / rc_board::GroupStore::file_name(static_cast<rc_board::GroupNumber>(g)), ec);
  if (!found) return std::nullopt;
  auto settings = load_settings(state_dir, default_settings(config));
  if (!settings) throw ArmctlError(settings.error());
  return DaemonState{state_dir, std::move(*settings)};
}

std::vector<std::string> import_daemon_state(const DaemonState& state, const ControllerConfig& config,
                                             CoreDevice& device) {
  std::vector<std::string> log;
  CoreLink link(device);
  const CoreDevice::Output host = device.swap_output([&link](const rc::Frame& f) { link.deliver(f); });
  robot_commands::ClientOptions options;
  options.servo_count = config.joints.back().number;
  robot_commands::Client client(link, options);
  // A request without a reply: was it taken? (the core counts what it ignores)
  auto taken = [&](const Status& sent) {
    const auto ignored = device.core().stats().ignored_frames;
    device.run_for(1ms);  // its settings record written
    return sent.ok() && device.core().stats().ignored_frames == ignored;
  };

  const ControllerSettings defaults = default_settings(config);
  const ControllerSettings& settings = state.settings;
  if (settings != defaults) {
    std::vector<std::uint8_t> offsets;
    int limits = 0;
    for (const auto& [number, joint] : settings.joints) {
      const auto servo = static_cast<std::uint8_t>(number);
      if (joint.saved_offset == 0) continue;
      if (taken(client.adjust_offset(servo, joint.saved_offset))) offsets.push_back(servo);
      else log.push_back(fmt::format("joint {}: its saved offset {} was not taken", number, joint.saved_offset));
    }
    // Each joint's limits that differ from the defaults; the joint BusServoInfo addressed
    // last (even with its defaults), so that it is the one addressed now.
    auto write_limits = [&](int number, const JointSettings& joint) {
      if (taken(client.write_bus_servo_info(joint.limits))) ++limits;
      else log.push_back(fmt::format("joint {}: its BusServoInfo limits were not taken", number));
    };
    for (const auto& [number, joint] : settings.joints)
      if (number != settings.info_joint && joint.limits != defaults.joints.at(number).limits)
        write_limits(number, joint);
    if (auto addressed = settings.joints.find(settings.info_joint); addressed != settings.joints.end())
      write_limits(addressed->first, addressed->second);
    if (!offsets.empty() && !taken(client.save_offsets(offsets)))
      log.push_back("the saved offsets could not be written");
    log.push_back(fmt::format("imported {}: {} saved offsets, {} joints' limits", settings_path(state.dir).string(),
                              offsets.size(), limits));
  }

  rc_board::GroupStore old(state.dir);
  for (const auto& p : old.problems()) log.push_back("state dir: " + p);
  int groups = 0;
  for (int g = 0; g < static_cast<int>(rc_board::kGroupCount); ++g) {
    const auto* group = old.find(static_cast<rc_board::GroupNumber>(g));
    if (group == nullptr) continue;
    std::vector<rc::GroupAction> actions;
    for (const auto& a : group->actions) actions.push_back(rc::GroupAction{a.milliseconds, a.positions});
    if (auto r = client.download_group(static_cast<std::uint8_t>(g), actions); r.ok()) {
      ++groups;
    } else {
      log.push_back(fmt::format("group {} ({}) not imported: {}", g, rc_board::GroupStore::file_name(
                                                                          static_cast<rc_board::GroupNumber>(g)).string(),
                                r.error().message));
    }
  }
  if (old.size() > 0)
    log.push_back(fmt::format("imported {} of {} action groups from {}", groups, old.size(), state.dir.string()));
  device.swap_output(host);
  log.push_back(fmt::format("the state is now {} in {}; the old files are left as they were",
                            CoreDevice::memory_file, state.dir.string()));
  return log;
}

}  // namespace armctl::arm_controller
