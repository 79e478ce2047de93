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

// What a contact is with: another body, or one of the scene's limits (scene/scene_limits.hpp).
enum class Limit { none, fence, joint_range };
const char* to_string(Limit limit);  // "collision", "fence", "joint range"

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
  // A limit broken rather than two bodies touching (docs/scene.md "Fence and reduced mode"):
  // `first` is what breaks it ("the tool point", "link 'hand'", "joint 'servo1'"), `second`
  // the limit ("the fence", "its reduced range -90.000..90.000 deg"), `depth` how far beyond
  // it (m, or rad for a revolute joint) and `point` the tool point.
  Limit limit = Limit::none;
  // The same two bodies as typed ids, for apps to show and match without reading the text
  // (a link outside the fence: first_body only; the tool point or a joint: neither).
  BodyId first_body, second_body;
};

// A joint's range in reduced mode (arm/reduced_mode.hpp), SI, with how people read it.
struct JointRange {
  std::size_t joint = 0;
  double lower = 0, upper = 0;
  std::string name;   // "joint 'servo1'"
  std::string words;  // "its reduced range -90.000..90.000 deg"
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
  // Reduced mode's joint ranges while it is on (empty: off or none set); the fence is the
  // scene's (Scene::fence, while on).
  std::vector<JointRange> joint_ranges;
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
  // The pairs in contact at `joints` (indices for `skip`), and how they are named. The
  // limits broken there count as pairs too, numbered after them (limit_breach).
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
  // The fence and reduced mode (docs/scene.md "Fence and reduced mode"), checked with the
  // pairs: the first limit broken at the configuration placed in `at` (`joints`), not in
  // `skip` (indices pairs_checked() and on: the tool point's fence, the links' fence, each
  // joint range), as a Contact whose `limit` says which.
  std::optional<Contact> limit_breach(std::span<const double> joints, Placement& at, std::span<const int> skip = {}) const;
  // One limit (index pairs_checked() and on, as touching gives it) at the configuration
  // placed in `at`: how far beyond it the arm is, as a Contact, or nothing when within it.
  std::optional<Contact> limit_at(int index, std::span<const double> joints, Placement& at) const {
    return limit_broken(std::size_t(index) - pairs_.size(), joints, at);
  }
  bool has_limits() const { return !limits_.empty(); }
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
  // The limits checked, in index order after the pairs (world_limits.cpp).
  enum class LimitItem { tool_in_fence, links_in_fence, joint_range };
  struct LimitCheck {
    LimitItem item = LimitItem::tool_in_fence;
    std::size_t range = 0;  // joint_range: which of arm_.joint_ranges
  };
  std::vector<LimitCheck> limits_;
  std::optional<Fence> fence_;  // the scene's, when on
  int tool_body_ = -1;
  std::optional<Contact> limit_broken(std::size_t k, std::span<const double> joints, Placement& at) const;
  // How far the tool point is inside the fence (its clearance), or nothing without a fence.
  std::optional<double> fence_margin(Placement& at) const;
  void add_limits();
  // reach_[body][joint]: how far a point of that body can be from the joint's axis (m);
  // for a prismatic joint 1 (the point moves as far as the joint).
  std::vector<std::vector<double>> reach_;
};

}  // namespace armctl::scene
