// What the web tests of the pure parts share: the xArm's model, and the status and message
// of the ApiError a request's parsing or check throws.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "arm/arm_model.hpp"
#include "web/api_error.hpp"

namespace armctl::web {

inline const arm::ArmModel& xarm() {
  static const arm::ArmModel m = arm::load_arm_model(arm::arm_file_path("xarm")).value();
  return m;
}

// The status and message of the ApiError `f` throws (a test failure if it throws none).
template <typename F>
std::pair<int, std::string> refusal(F f) {
  try {
    f();
  } catch (const ApiError& e) {
    return {e.status(), e.what()};
  }
  ADD_FAILURE() << "not refused";
  return {0, ""};
}

}  // namespace armctl::web
