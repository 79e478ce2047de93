// The locally generated FollowJointTrajectory action is control_msgs' on the wire: the same
// type names and MD5 sums, so that clients built against control_msgs 1.5 (MoveIt, rqt, any
// actionlib client) connect. The expected sums are control_msgs' published ones, as its
// generated code carries them (e.g. the rosserial ros_lib for control_msgs, in the public
// repository IFL-CAMP/supra: rosserial_libs/ros_lib/control_msgs/FollowJointTrajectory*.h
// and JointTolerance.h, getMD5(); the same sums in other languages' control_msgs bindings).
#include <string>

#include <gtest/gtest.h>

#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointTolerance.h>

namespace {

template <typename M>
std::string md5() {
  return ros::message_traits::MD5Sum<M>::value();
}
template <typename M>
std::string type() {
  return ros::message_traits::DataType<M>::value();
}

TEST(RosMessages, FollowJointTrajectoryHasControlMsgsSums) {
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryAction>(), "bc4f9b743838566551c0390c65f1a248");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryActionGoal>(), "cff5c1d533bf2f82dd0138d57f4304bb");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryActionResult>(), "c4fb3b000dc9da4fd99699380efcc5d9");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryActionFeedback>(), "d8920dc4eae9fc107e00999cce4be641");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryGoal>(), "69636787b6ecbde4d61d711979bc7ecb");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryResult>(), "493383b18409bfb604b4e26c676401d2");
  EXPECT_EQ(md5<control_msgs::FollowJointTrajectoryFeedback>(), "10817c60c2486ef6b33e97dcd87f4474");
  EXPECT_EQ(md5<control_msgs::JointTolerance>(), "f544fe9c16cf04547e135dd6063ff5be");
}

TEST(RosMessages, FollowJointTrajectoryHasControlMsgsTypeNames) {
  EXPECT_EQ(type<control_msgs::FollowJointTrajectoryActionGoal>(), "control_msgs/FollowJointTrajectoryActionGoal");
  EXPECT_EQ(type<control_msgs::FollowJointTrajectoryActionResult>(), "control_msgs/FollowJointTrajectoryActionResult");
  EXPECT_EQ(type<control_msgs::FollowJointTrajectoryActionFeedback>(),
            "control_msgs/FollowJointTrajectoryActionFeedback");
  EXPECT_EQ(control_msgs::FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED, -4);
  EXPECT_EQ(control_msgs::FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED, -5);
}

}  // namespace
