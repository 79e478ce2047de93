// The arm's links and the scene as one collision world (FCL underneath): whether the arm at
// given joint values touches itself or something of the scene, which two bodies, how deep,
// and how far it stays from everything. Built once per arm and scene; const and shared
// across threads (a query keeps its transforms on its own stack).
//
// What is checked: every pair of links except the arm file's allowed pairs and links that
// are joined (parent and child, whose shapes meet at the joint); every link that moves
// against every scene object; parts held by the tool against the scene and every link but
// the ones that hold them (the tool's link, its parent and that parent's other children:
// the fingers). Links fixed to the base never move, so they are not checked against the
// scene (the base stands on the table).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "motion/link_bodies.hpp"
#include "scene/scene.hpp"

namespace armctl::scene {

// Clearances beyond this are not measured ("more than 50 mm"): a distance query costs ten
// collision checks, and nobody steers by the clearance of things that far apart.
inline constexpr double kClearanceHorizon = 0.05;  // m

// Which body, for a program (a dashboard drawing it red): a link of the URDF or a scene
// object, by its name. The words for people are Contact::first and second.
struct BodyId {
  enum class Kind { link, object } kind = Kind::link;
  std::string name;  // the link's or the scene object's; empty: not known
};

struct Contact {
  std::string first, second;  // "link 'hand'", "the table 'table'", "box 'feeder'"
  double depth = 0;           // m: how far they overlap
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // base frame
  BodyId first_body, second_body;  // the same two bodies
};

struct Clearance {
  double distance = kClearanceHorizon;  // m; kClearanceHorizon: nothing nearer
  std::string first, second;            // empty when nothing is nearer than the horizon
};

// The arm's side of the world: its links, the pairs never checked, where held parts hang.
struct ArmBodies {
  std::shared_ptr<const motion::LinkBodies> links;
  std::vector<std::pair<std::string, std::string>> allowed;  // link names
  std::string tool_link;
  Eigen::Isometry3d tool_frame = Eigen::Isometry3d::Identity();  // in the tool link
  // Per joint, the largest |value| it reaches (m for a prismatic joint): bounds how far a
  // point of a link can move when the joints turn (displacement_bound).
  std::vector<double> joint_reach;
};

class CollisionWorld {
 public:
  // Errors (invalid_config): an allowed pair or the tool link naming no link.
  static Result<std::shared_ptr<const CollisionWorld>> build(ArmBodies arm, Scene scene);

  const Scene& scene() const { return scene_; }
  const ArmBodies& arm() const { return arm_; }
  std::size_t pairs_checked() const { return pairs_.size(); }

  // Whether anything touches at `joints` (every joint of the arm, SI). The fast question.
  // `skip`: pairs (touching's indices) not asked about.
  bool collides(std::span<const double> joints, std::span<const int> skip = {}) const;
  // The deepest contact at `joints`, or nothing.
  std::optional<Contact> contact(std::span<const double> joints, std::span<const int> skip = {}) const;
  // The pairs in contact at `joints` (indices for `skip`), and how they are named.
  std::vector<int> touching(std::span<const double> joints) const;
  std::pair<std::string, std::string> pair_names(int pair) const;
  // The smallest distance between two bodies that are checked, when below `below` (at most
  // kClearanceHorizon): pairs whose bounding boxes are farther apart are not measured.
  Clearance clearance(std::span<const double> joints, double below = kClearanceHorizon,
                      std::span<const int> skip = {}) const;
  // An upper bound on how far any point of any checked body moves when the joints go from
  // `from` to `to` along a straight line in joint space (m).
  double displacement_bound(std::span<const double> from, std::span<const double> to) const;

  // Pair by pair, for a motion's check that asks FCL only about pairs that may have come near
  // since it last measured them (check_motion): where every body is at one configuration,
  // and each pair's questions about it.
  // Every link's frame and every shape's centre; a shape's frame and bounding box only once
  // a pair query needs them (most steps of a motion ask no pair at all).
  struct Placement {
    std::vector<Eigen::Isometry3d> bodies, items;  // every link's frame, every shape's
    std::vector<Eigen::Vector3d> centres;          // every shape's centre
    std::vector<Eigen::Vector3d> low, high;        // every shape's bounding box
    std::vector<char> placed;                      // whether items, low and high hold for a shape
  };
  void place(std::span<const double> joints, Placement& at) const;
  // Whether the pair (touching's indices) touches: its bounding boxes first, then FCL.
  bool pair_touches(int pair, Placement& at) const;
  // The gap between the pair's bounding boxes: never more than the shapes' distance, and cheap.
  double pair_gap(int pair, Placement& at) const;
  // The shapes' distance (FCL; 0 when they touch).
  double pair_distance(int pair, Placement& at) const;
  // For a short step from the configuration placed in `at`, in which joint j travels
  // `travel[j]` (the sum of |dq| over the step's pieces: a joint that turns back counts
  // both ways): an upper bound on how far any point of any body moves (from the arm's
  // geometry at the start: how far each shape is from each joint's axis there, never more
  // than displacement_bound's farthest), and, when `closing` is given, per pair how much
  // nearer its two bodies can come to each other. For a pair only the joints between its
  // two bodies count: a joint both hang from moves them alike. Valid for steps whose result
  // is at most `pad` / 2: along the step no point comes nearer to or farther from an axis
  // than that (check_motion's steps, pad twice the resolution).
  double step_displacement_bound(const Placement& at, std::span<const double> travel, double pad,
                                 std::vector<double>* closing = nullptr) const;

  struct Item;  // one shape (collision_world.cpp)
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

 private:
  CollisionWorld() = default;
  // The shape's frame and bounding box in `at`, on first need.
  void complete(Placement& at, std::size_t item) const;
  void place_every_shape(std::span<const double> joints, Placement& at) const;
  template <typename Visit>
  void each_touching(std::span<const double> joints, std::span<const int> skip, bool with_contact, Visit&& visit) const;
  ArmBodies arm_;
  Scene scene_;
  std::vector<Item> items_;
  struct Pair {
    int first = 0, second = 0;  // item indices
    // How many of each item's moving links (Item::chain, from its own up) the other item does
    // not hang from: the joints that move the two against each other.
    int first_own = 0, second_own = 0;
  };
  std::vector<Pair> pairs_;
  // reach_[body][joint]: how far a point of that body can be from the joint's axis (m);
  // for a prismatic joint 1 (the point moves as far as the joint).
  std::vector<std::vector<double>> reach_;
};

}  // namespace armctl::scene
