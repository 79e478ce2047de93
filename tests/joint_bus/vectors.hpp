// Loads the byte-exact joint bus vectors (ARMCTL_VECTORS_DIR/joint-bus.json).
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scripted_link.hpp"

namespace armctl::test {

struct Transcript {
  std::string name;
  std::vector<Step> steps;
};

inline nlohmann::json load_joint_bus_vectors() {
  std::ifstream in(std::string(ARMCTL_VECTORS_DIR) + "/joint-bus.json");
  return nlohmann::json::parse(in);
}

inline std::vector<Transcript> load_transcripts() {
  std::vector<Transcript> out;
  const nlohmann::json all = load_joint_bus_vectors();
  for (const auto& t : all.at("transcripts")) {
    Transcript tr{t.at("name").get<std::string>(), {}};
    for (const auto& s : t.at("steps")) {
      tr.steps.push_back(Step{s.at(0).get<std::string>() == "master", s.at(1).get<std::string>()});
    }
    out.push_back(std::move(tr));
  }
  return out;
}

}  // namespace armctl::test
