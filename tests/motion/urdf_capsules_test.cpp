// <capsule> collision shapes in a URDF (motion/urdf_capsules.hpp): read as capsules by the
// link bodies, given to urdfdom as cylinders, drawn for viewers as a cylinder and two
// spheres; a bad one is refused naming the link and the size.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "motion/link_bodies.hpp"
#include "motion/urdf_capsules.hpp"
#include "motion/urdf_for_viewers.hpp"
#include "motion/urdf_model.hpp"

namespace armctl::motion {
namespace {

using ::testing::HasSubstr;

// A base and one link turning about z, its body a capsule standing 40 mm up, turned 90 deg
// about x so that its axis lies along -y; its visual a capsule too.
std::string one_capsule(const std::string& capsule = R"(radius="0.02" length="0.1")") {
  return R"(<?xml version="1.0"?>
<robot name="stick">
  <link name="base_link"/>
  <link name="stick">
    <!-- the stick's body -->
    <visual><origin xyz="0 0 0.04" rpy="1.5707963267948966 0 0"/><geometry><capsule )" +
         capsule + R"(/></geometry></visual>
    <collision><origin xyz="0 0 0.04" rpy="1.5707963267948966 0 0"/><geometry><capsule )" + capsule +
         R"(/></geometry></collision>
    <collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision>
  </link>
  <joint name="turn" type="revolute">
    <parent link="base_link"/><child link="stick"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/>
  </joint>
</robot>
)";
}

TEST(UrdfCapsules, TheLinkBodyIsACapsuleOfItsSizeWhereTheUrdfPutsIt) {
  const std::vector<std::string> joints{"turn"};
  auto bodies = read_link_bodies(one_capsule(), "base_link", joints);
  ASSERT_TRUE(bodies) << bodies.error().message;
  const LinkBody& stick = bodies->bodies[std::size_t(*bodies->find("stick"))];
  ASSERT_EQ(stick.shapes.size(), 2u);
  const Shape& capsule = stick.shapes[0];
  EXPECT_EQ(capsule.kind, Shape::Kind::capsule);
  EXPECT_TRUE(capsule.size.isApprox(Eigen::Vector3d(0.02, 0.1, 0), 1e-12));
  EXPECT_TRUE(capsule.pose.translation().isApprox(Eigen::Vector3d(0, 0, 0.04), 1e-12));
  EXPECT_TRUE(capsule.pose.linear().col(2).isApprox(Eigen::Vector3d(0, -1, 0), 1e-9));
  EXPECT_EQ(stick.shapes[1].kind, Shape::Kind::box);  // the next <collision> is still the box
  EXPECT_STREQ(to_string(Shape::Kind::capsule), "capsule");
  // Its extent: the segment grown by the radius.
  EXPECT_NEAR(bounding_radius(capsule), 0.07, 1e-12);
  Eigen::Vector3d low, high;
  world_bounds(capsule, capsule.pose, low, high);
  EXPECT_TRUE(low.isApprox(Eigen::Vector3d(-0.02, -0.07, 0.02), 1e-9)) << low.transpose();
  EXPECT_TRUE(high.isApprox(Eigen::Vector3d(0.02, 0.07, 0.06), 1e-9)) << high.transpose();
  // The chain reads past it.
  EXPECT_TRUE(read_urdf_chain(one_capsule(), "base_link", "stick"));
}

TEST(UrdfCapsules, ABadCapsuleIsRefusedNamingTheLinkAndTheSize) {
  const std::vector<std::string> joints{"turn"};
  for (const char* bad : {R"(radius="0.02")", R"(radius="0" length="0.1")", R"(radius="0.02" length="-1")",
                          R"(radius="x" length="0.1")"}) {
    auto r = read_link_bodies(one_capsule(bad), "base_link", joints);
    ASSERT_FALSE(r) << bad;
    EXPECT_THAT(r.error().message, HasSubstr("link 'stick' <collision> 1: <capsule ")) << bad;
    EXPECT_THAT(r.error().message, HasSubstr("wants a length above 0 (m)")) << bad;
  }
  // Text without capsules is given to urdfdom as it is.
  auto plain = without_capsules("<robot name=\"r\"><link name=\"a\"/></robot>");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->xml, "<robot name=\"r\"><link name=\"a\"/></robot>");
  EXPECT_TRUE(plain->capsules.empty());
}

// Viewers know no capsule: they get its cylinder and a sphere on each end.
TEST(UrdfCapsules, ViewersGetACylinderAndTwoSpheres) {
  auto text = urdf_for_viewers(one_capsule(), {});
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(text->find("<capsule"), std::string::npos) << *text;
  EXPECT_NE(text->find("the stick's body"), std::string::npos);  // comments kept
  std::vector<UrdfCapsule> capsules;
  auto model = parse_urdf_model(*text, &capsules);
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(capsules.empty());
  const auto link = (*model)->getLink("stick");
  ASSERT_EQ(link->collision_array.size(), 4u);  // cylinder, two spheres, the box
  ASSERT_EQ(link->visual_array.size(), 3u);
  const auto& cylinder = static_cast<const urdf::Cylinder&>(*link->collision_array[0]->geometry);
  EXPECT_EQ(link->collision_array[0]->geometry->type, urdf::Geometry::CYLINDER);
  EXPECT_DOUBLE_EQ(cylinder.radius, 0.02);
  EXPECT_DOUBLE_EQ(cylinder.length, 0.1);
  // The ends' centres 50 mm either way along the capsule's axis (-y), 40 mm up.
  for (std::size_t i : {1u, 2u}) {
    const auto& c = *link->collision_array[i];
    ASSERT_EQ(c.geometry->type, urdf::Geometry::SPHERE) << i;
    EXPECT_DOUBLE_EQ(static_cast<const urdf::Sphere&>(*c.geometry).radius, 0.02);
    EXPECT_NEAR(c.origin.position.x, 0, 1e-9);
    EXPECT_NEAR(std::abs(c.origin.position.y), 0.05, 1e-9) << i;
    EXPECT_NEAR(c.origin.position.z, 0.04, 1e-9);
  }
  EXPECT_NEAR(link->collision_array[1]->origin.position.y + link->collision_array[2]->origin.position.y, 0, 1e-9);
  EXPECT_EQ(link->collision_array[3]->geometry->type, urdf::Geometry::BOX);
  EXPECT_EQ(link->visual_array[2]->geometry->type, urdf::Geometry::SPHERE);
}

}  // namespace
}  // namespace armctl::motion
