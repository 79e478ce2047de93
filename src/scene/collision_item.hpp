// One shape of the collision world (scene/collision_world.hpp), for the files that make up
// the world: collision_world.cpp (pairs) and world_limits.cpp (the fence).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <fcl/geometry/collision_geometry.h>

#include "scene/collision_world.hpp"

namespace armctl::scene {

struct CollisionWorld::Item {
  std::string label;
  int body = -1;         // the link it moves with; -1: fixed in the base frame
  motion::Shape shape;   // its pose in the link's frame (or the base frame)
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  bool scene = false;    // a scene object (fixed or held), not a link
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // fixed ones: bounds
  std::vector<int> chain;  // the links with a joint it hangs from, its own first; none when fixed
  BodyId id;               // which link or scene object it is
  double radius = 0;       // motion::bounding_radius(shape), asked at every step of a motion check
};

}  // namespace armctl::scene
