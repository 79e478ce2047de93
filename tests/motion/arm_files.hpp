// The shipped URDFs and their chains, for the motion tests.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "kdl_oracle.hpp"
#include "motion/scara_kinematics.hpp"
#include "motion/urdf_chain.hpp"
#include "motion/xarm_kinematics.hpp"

namespace armctl::motion::testing {

inline std::string urdf_path(const std::string& arm) { return std::string(ARMCTL_SOURCE_DIR) + "/config/" + arm + ".urdf"; }
inline std::string urdf_text(const std::string& arm) { return read_text(urdf_path(arm)); }

inline UrdfChain shipped_chain(const std::string& arm) {
  auto chain = read_urdf_chain(urdf_text(arm), "base_link", "tool");
  if (!chain) throw std::runtime_error(chain.error().message);
  return chain.value();
}

// A family's kinematics factory (the built-in families' own; arm/arm_families.hpp names them).
using MakeKinematics = Result<std::unique_ptr<Kinematics>> (*)(const UrdfChain&, std::span<const PositionLimits>);
inline MakeKinematics family_of(const std::string& arm) {
  return arm == "scara" ? make_scara_kinematics : make_xarm_kinematics;
}

inline std::unique_ptr<Kinematics> shipped_kinematics(const std::string& arm) {
  const UrdfChain chain = shipped_chain(arm);
  const auto limits = urdf_position_limits(chain);
  auto k = family_of(arm)(chain, limits);
  if (!k) throw std::runtime_error(k.error().message);
  return std::move(k).value();
}

// The URDF text with the first `from` replaced by `to` (the test fails if `from` is absent).
inline std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "edit target not found: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace armctl::motion::testing
