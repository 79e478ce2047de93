// Random scenes for the collision tests: `count` objects of every kind (10..70 mm) within an
// arm's reach, at random orientations, drawn from `rng` alone (the same scenes whatever ran
// before: Eigen's UnitRandom would draw from std::rand).
#pragma once

#include <cmath>
#include <random>
#include <string>

#include "scene/scene.hpp"

namespace armctl::scene::testing {

inline Scene random_scene(double reach, int count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> normal;
  Scene scene;
  for (int k = 0; k < count; ++k) {
    SceneObject o;
    o.name = "o" + std::to_string(k);
    o.shape.kind = static_cast<motion::Shape::Kind>(k % 4);  // box, cylinder, sphere, capsule
    o.shape.size = {0.01 + 0.06 * unit(rng), 0.01 + 0.06 * unit(rng), 0.01 + 0.06 * unit(rng)};
    const double r = reach * unit(rng), a = 2 * M_PI * unit(rng);
    o.shape.pose.translation() = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), reach * (unit(rng) - 0.3));
    o.shape.pose.linear() =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
    scene.objects.push_back(o);
  }
  return scene;
}

}  // namespace armctl::scene::testing
