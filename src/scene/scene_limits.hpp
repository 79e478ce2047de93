// The fence and reduced mode of a scene (docs/scene.md "Fence and reduced mode"): a box in
// the arm's base frame the tool point (and, if asked, every link) must stay inside, and a
// mode with a cap on the tool's speed and narrower joint ranges. Each is on when configured
// and switched off and on at run time (Arm::set_fence, Arm::set_reduced_mode). Read from and
// written to a scene file's "fence" and "reduced" keys; held in SI like the rest of a scene,
// except the joint ranges, kept as the file gives them (degrees, or millimetres for a
// prismatic joint) because only the arm knows which joint is which (arm/reduced_mode.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace armctl::scene {

struct Fence {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // m, base frame
  bool links = false;  // every moving link's collision shapes inside too, not only the tool point
  bool on = true;
};

struct ReducedJointRange {
  std::string joint;
  double lower = 0, upper = 0;  // deg, or mm for a prismatic joint
};

struct ReducedMode {
  std::optional<double> tool_speed;  // m/s of the tool point
  std::vector<ReducedJointRange> joints;
  bool on = true;
};

// `at` is the key's path for errors ("fence"); `source` names the file. Both throw
// ArmctlError (invalid_config) naming the key, the value and what is allowed.
Fence read_fence(const std::string& source, const nlohmann::json& v, const std::string& at);
ReducedMode read_reduced(const std::string& source, const nlohmann::json& v, const std::string& at);
// As a scene file writes them (millimetres, degrees): what read_fence / read_reduced read back.
nlohmann::json fence_json(const Fence& fence);
nlohmann::json reduced_json(const ReducedMode& reduced);

}  // namespace armctl::scene
