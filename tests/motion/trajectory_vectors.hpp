// Loads ../shared/vectors/trajectory-sync-7dof.json (ARMCTL_VECTORS_DIR): synchronized
// 7-joint cases with the time-optimal duration Ruckig computed for each.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "motion/trajectory.hpp"

namespace armctl::motion::testing {

struct SyncVector {
  std::string name;     // set and index, for messages
  bool hard = false;    // armctl was longer than the optimum when the vectors were made
  double duration = 0;  // the optimum, s
  TrajectoryInput in;
};

inline std::vector<SyncVector> load_sync_vectors(const std::string& path) {
  std::ifstream file(path);
  const nlohmann::json doc = nlohmann::json::parse(file);
  std::vector<SyncVector> out;
  for (const auto& c : doc.at("cases")) {
    SyncVector v;
    v.name = c.at("set").get<std::string>() + "#" + std::to_string(c.at("index").get<long>());
    v.hard = c.at("hard").get<bool>();
    v.duration = c.at("duration").get<double>();
    const auto& joints = c.at("joints");
    v.in.joints = int(joints.size());
    for (int i = 0; i < v.in.joints; ++i) {
      const auto& j = joints[std::size_t(i)];
      v.in.position[i] = j.at("p0"), v.in.velocity[i] = j.at("v0"),
      v.in.acceleration[i] = j.at("a0");
      v.in.target_position[i] = j.at("pf"), v.in.target_velocity[i] = j.at("vf");
      v.in.max_velocity[i] = j.at("vmax"), v.in.max_acceleration[i] = j.at("amax");
      v.in.max_jerk[i] = j.at("jmax");
    }
    out.push_back(v);
  }
  return out;
}

inline std::string sync_vectors_path() {
  return std::string(ARMCTL_VECTORS_DIR) + "/trajectory-sync-7dof.json";
}

}  // namespace armctl::motion::testing
