// Joint-bus devices: the embedded simulated arm here, everything else from the SDK.
#include <fmt/core.h>

#include "core/debug_log.hpp"
#include "core/error.hpp"
#include "core/miscalibration.hpp"

#include "devices/device_registry/device_registry.hpp"
#include "devices/joint_sim/sim_arm.hpp"

namespace armctl::devices {

namespace {

class EmbeddedSim final : public joint_bus::BusConnection {
 public:
  explicit EmbeddedSim(const joint_bus::SimDevice& d) : dialect_(d.dialect) {
    joint_sim::ArmConfig config = d.config.empty()
                                      ? joint_sim::load_arm_config(joint_sim::default_arm_config_path())
                                      : joint_sim::load_arm_config(d.config);
    if (d.baud) config.baud = *d.baud;
    for (auto& joint : config.joints)
      for (int n : d.swapped_joints) joint.hardware.leads_swapped = joint.hardware.leads_swapped || joint.number == n;
    // dialect=legacy: every joint as if flashed with DIALECT=legacy (legacy-master mode).
    joint_sim::SimArmOptions options;
    options.joints.legacy_master = d.dialect == joint_bus::Dialect::legacy;
    if (d.miscal) {
      options.miscal = make_miscalibration(MiscalArm::scara, *d.miscal);
      debug_log("embedded simulated arm: " + describe(*options.miscal));
    }
    arm_ = std::make_unique<joint_sim::SimArm>(std::move(config), options);
    if (!d.dead_joints.empty()) {
      joint_sim::FaultPlan faults;
      for (int j : d.dead_joints) faults.dead_joint(j);
      arm_->set_fault_plan(std::move(faults));
    }
  }
  transport::JointBusLink& link() override { return arm_->link(); }
  joint_bus::MasterOptions default_options() const override {
    joint_bus::MasterOptions o;
    o.dialect = dialect_;
    return o;
  }
  std::string description() const override {
    return fmt::format("embedded simulated arm at {} baud{}{}", arm_->config().baud,
                       dialect_ == joint_bus::Dialect::legacy ? ", legacy-master joints" : "",
                       arm_->miscalibration() ? ", mis-assembled" : "");
  }
  joint_sim::SimArm& arm() { return *arm_; }

 private:
  joint_bus::Dialect dialect_;
  std::unique_ptr<joint_sim::SimArm> arm_;
};

}  // namespace

joint_sim::SimArm* embedded_sim_arm(joint_bus::BusConnection& connection) {
  auto* sim = dynamic_cast<EmbeddedSim*>(&connection);
  return sim ? &sim->arm() : nullptr;
}

Result<std::unique_ptr<joint_bus::BusConnection>> open_joint_bus(const joint_bus::DeviceUri& uri) {
  // Devices are opened by constructors, which throw: this is where that becomes a Result.
  try {
    if (const auto* s = std::get_if<joint_bus::SimDevice>(&uri)) {
      return std::unique_ptr<joint_bus::BusConnection>(std::make_unique<EmbeddedSim>(*s));
    }
    return joint_bus::open_bus(uri);
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

Result<std::unique_ptr<joint_bus::BusConnection>> open_joint_bus(std::string_view uri) {
  auto parsed = joint_bus::parse_device_uri(uri);
  if (!parsed) return parsed.error();
  return open_joint_bus(*parsed);
}

}  // namespace armctl::devices
