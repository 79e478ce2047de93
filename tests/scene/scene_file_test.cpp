// Scene files (docs/scene.md): what they may say, in millimetres and degrees, and the error
// every mistake gets (the key path, the value, what is allowed; nothing kept).
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "scene/scene.hpp"

namespace armctl::scene {
namespace {

std::string error_of(const std::string& text) {
  auto s = parse_scene(text, "s.json");
  EXPECT_FALSE(s.ok()) << text;
  return s ? std::string() : s.error().message;
}

TEST(SceneFile, ReadsEveryKindInMillimetresAndDegrees) {
  auto s = parse_scene(R"({"objects": [
      {"name": "desk", "table": {"top": -5, "size": [800, 600], "center": [150, 0]}},
      {"name": "box", "box": [60, 80, 100], "at": [170, 0, 50], "rpy": [0, 0, 90]},
      {"name": "can", "cylinder": {"radius": 30, "length": 120}, "at": [0, 200, 60]},
      {"name": "ball", "sphere": {"radius": 25}, "at": [100, -100, 25]},
      {"name": "door", "keep_out": true, "box": [200, 100, 300], "at": [0, -220, 150]},
      {"name": "part", "attached": "tool", "box": [20, 20, 40], "at": [20, 0, 0]},
      {"name": "pipe", "capsule": {"radius": 15, "length": 200}, "at": [0, 250, 40], "rpy": [0, 90, 0]}]})",
                       "s.json");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->objects.size(), 7u);
  EXPECT_EQ(s->objects[6].shape.kind, motion::Shape::Kind::capsule);
  EXPECT_TRUE(s->objects[6].shape.size.isApprox(Eigen::Vector3d(0.015, 0.2, 0), 1e-12));
  EXPECT_EQ(describe(s->objects[6]), "capsule 'pipe'");
  const auto& desk = s->objects[0];
  EXPECT_EQ(desk.role, ObjectRole::table);
  EXPECT_NEAR(desk.shape.pose.translation().z() + 0.5 * desk.shape.size.z(), -0.005, 1e-12);  // the top
  EXPECT_NEAR(desk.shape.size.x(), 0.8, 1e-12);
  EXPECT_NEAR(desk.shape.pose.translation().x(), 0.15, 1e-12);
  const auto& box = s->objects[1];
  EXPECT_EQ(box.shape.kind, motion::Shape::Kind::box);
  EXPECT_NEAR(box.shape.size.y(), 0.08, 1e-12);
  // 90 deg about z: the box's x axis points along the base's y.
  EXPECT_NEAR(box.shape.pose.linear().col(0).y(), 1, 1e-12);
  EXPECT_EQ(s->objects[2].shape.kind, motion::Shape::Kind::cylinder);
  EXPECT_NEAR(s->objects[2].shape.size.y(), 0.12, 1e-12);
  EXPECT_NEAR(s->objects[3].shape.size.x(), 0.025, 1e-12);
  EXPECT_EQ(s->objects[4].role, ObjectRole::keep_out);
  EXPECT_TRUE(s->objects[5].attached);
  EXPECT_EQ(describe(s->objects[4]), "keep-out zone 'door'");
  EXPECT_EQ(describe(s->objects[0]), "the table 'desk'");
}

TEST(SceneFile, WritesWhatItReadsBack) {
  auto s = parse_scene(R"({"objects": [{"name": "desk", "table": {"top": 12}},
      {"name": "box", "box": [60, 80, 100], "at": [170, 0, 50], "rpy": [10, 20, 30]},
      {"name": "part", "attached": "tool", "sphere": {"radius": 5}, "at": [1, 2, 3]},
      {"name": "pipe", "capsule": {"radius": 15, "length": 200}, "at": [0, 250, 40], "rpy": [0, 90, 0]}]})",
                       "s.json");
  ASSERT_TRUE(s.ok()) << s.error().message;
  auto back = parse_scene(scene_json(*s), "written");
  ASSERT_TRUE(back.ok()) << back.error().message << "\n" << scene_json(*s);
  ASSERT_EQ(back->objects.size(), s->objects.size());
  for (std::size_t i = 0; i < s->objects.size(); ++i) {
    EXPECT_EQ(back->objects[i].name, s->objects[i].name);
    EXPECT_EQ(back->objects[i].role, s->objects[i].role);
    EXPECT_EQ(back->objects[i].attached, s->objects[i].attached);
    EXPECT_TRUE(back->objects[i].shape.pose.isApprox(s->objects[i].shape.pose, 1e-9)) << i;
    EXPECT_TRUE(back->objects[i].shape.size.isApprox(s->objects[i].shape.size, 1e-9)) << i;
    EXPECT_EQ(back->objects[i].shape.kind, s->objects[i].shape.kind) << i;
  }
}

TEST(SceneFile, TheShippedExampleReads) {
  auto s = load_scene(std::string(ARMCTL_SOURCE_DIR) + "/examples/scenes/xarm-desk.json");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->objects.size(), 3u);
}

TEST(SceneFile, EveryMistakeNamesTheKeyAndWhatIsAllowed) {
  EXPECT_EQ(error_of(R"({})"), "s.json: objects: missing");
  EXPECT_EQ(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "at": [0, 0, 0], "colour": 1}]})"),
            "s.json: objects[0].colour: unknown key (allowed here: comment, at, attached, box, capsule, cylinder, keep_out, name, rpy, sphere, table)");
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "capsule": {"radius": 5}, "at": [0, 0, 0]}]})")
                .find("objects[0].capsule.length: missing"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "capsule": {"radius": 5, "length": 1, "height": 2}, "at": [0, 0, 0]}]})")
                .find("objects[0].capsule.height: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1], "at": [0, 0, 0]}]})")
                .find("objects[0].box: must be an array of 3 numbers in 0.1..10000 (mm)"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 0], "at": [0, 0, 0]}]})")
                .find("objects[0].box[2]: 0 is outside the allowed range 0.1..10000"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "sphere": {"radius": 1}, "at": [0, 0, 0]}]})")
                .find("2 shapes given; wants exactly one of box"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1]}]})").find("objects[0].at: missing"), std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "at": [0, 0, 0]}, {"name": "a", "sphere": {"radius": 1}, "at": [0, 0, 0]}]})")
                .find("objects[1].name: 'a' names two objects"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a b", "box": [1, 1, 1], "at": [0, 0, 0]}]})").find("objects[0].name: \"a b\": wants 1..40 of"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "at": [0, 0, 0], "attached": "gripper"}]})")
                .find("the only place a part can be held is \"tool\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "t", "table": {"top": 0}, "at": [0, 0, 0]}]})").find("a table is placed by its top"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "at": [0, 0, 1e9]}]})").find("objects[0].at[2]"), std::string::npos);
  EXPECT_NE(error_of(R"({"objects": [{"name": "a", "box": [1, 1, 1], "at": [0, 0, 0], "rpy": [0, 0, 400]}]})")
                .find("objects[0].rpy[2]: 400 is outside the allowed range -360..360"),
            std::string::npos);
  EXPECT_NE(error_of("not json").find("s.json:"), std::string::npos);
}

TEST(SceneEdit, AddsReplacesAndRemovesOneObjectAndARefusalChangesNothing) {
  const Scene desk = parse_scene(R"({"objects": [{"name": "desk", "table": {"top": 0}}]})", "s.json").value();
  auto added = with_object(desk, R"({"name": "crate", "box": [60, 60, 80], "at": [150, 0, 40]})", "body");
  ASSERT_TRUE(added) << added.error().message;
  ASSERT_EQ(added->objects.size(), 2u);
  EXPECT_EQ(added->objects[1].name, "crate");
  EXPECT_EQ(desk.objects.size(), 1u);  // a new value
  auto moved = with_object(*added, R"({"name": "crate", "sphere": {"radius": 20}, "at": [0, 150, 20]})", "body");
  ASSERT_TRUE(moved) << moved.error().message;
  ASSERT_EQ(moved->objects.size(), 2u);
  EXPECT_EQ(moved->objects[1].shape.kind, motion::Shape::Kind::sphere);
  EXPECT_NEAR(moved->objects[1].shape.pose.translation().y(), 0.150, 1e-12);
  // The same checks as a file's, the key named without a list index.
  auto bad = with_object(*added, R"({"name": "crate", "box": [60, 60], "at": [150, 0, 40]})", "body");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::invalid_config);
  EXPECT_NE(bad.error().message.find("body: box: must be an array of 3 numbers"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(with_object(*added, "[1, 2]", "body"));
  EXPECT_FALSE(with_object(*added, R"({"name": "bad name", "box": [1, 1, 1], "at": [0, 0, 0]})", "body"));
  auto removed = without_object(*moved, "crate");
  ASSERT_TRUE(removed) << removed.error().message;
  EXPECT_EQ(removed->objects.size(), 1u);
  auto unknown = without_object(*moved, "bin");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(unknown.error().message.find("(the scene holds: desk, crate)"), std::string::npos) << unknown.error().message;
  // No more than a file may hold.
  Scene full;
  for (int i = 0; i < 200; ++i)
    full = with_object(full, R"({"name": "b)" + std::to_string(i) + R"(", "box": [1, 1, 1], "at": [0, 0, 0]})", "body").value();
  auto over = with_object(full, R"({"name": "one_more", "box": [1, 1, 1], "at": [0, 0, 0]})", "body");
  ASSERT_FALSE(over);
  EXPECT_NE(over.error().message.find("remove one first"), std::string::npos) << over.error().message;
}

TEST(SceneFile, ANonRegularFileIsRefusedBeforeItIsRead) {
  auto s = load_scene("/dev/zero");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("scene file"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace armctl::scene
