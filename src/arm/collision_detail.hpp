// The detail of an error because a motion would collide (Error::detail), wherever it is
// found: the planner refusing a plan before anything moves (arm/plan_moves.hpp), or the
// executor's look-ahead stopping a motion before contact once the scene changed under it
// (arm/motion_executor.hpp). Apps map it to their own form (Python's detail "collision").
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "scene/collision_world.hpp"

namespace armctl::arm {

struct CollisionDetail {
  scene::Contact contact;  // the two bodies and how deep
  std::size_t first_move = 0, last_move = 0;  // the piece's moves
  std::size_t line = 0;  // its first move's line in a file (0: not from a file)
  double fraction = 0;   // how far into the piece's motion, 0..1
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();  // base frame, m
  std::vector<double> joints;  // every joint there, SI
  // Found while the arm moved (the look-ahead): it was stopped before the contact, at
  // `stopped_at` (0..1 of the motion); false: refused before anything moved.
  bool while_moving = false;
  double stopped_at = 0;
};

}  // namespace armctl::arm
