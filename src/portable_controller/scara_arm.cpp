#include "portable_controller/scara_arm.hpp"

namespace armctl {
namespace controller {

// number, clicks at 0, clicks at 1000, soft min, soft max, speed, acceleration, zone
const JointSetup scara_joints[scara_joint_count] = {
    {1, -20000, 20000, -15000, 20000, 12000, 40000, 20},  // Z
    {2, -20000, 20000, -20000, 20000, 8000, 15000, 20},   // SHOULDER
    {3, -20000, 20000, -20000, 20000, 12000, 40000, 20},  // UAE
    {4, -10000, 10000, -10000, 10000, 12000, 40000, 20},  // UAJ
    {5, -10000, 10000, -10000, 10000, 12000, 40000, 20},  // SKE
    {6, -10000, 10000, -10000, 10000, 12000, 40000, 20},  // SKF
    {7, -5000, 5000, -5000, 5000, 12000, 40000, 20},      // SKG (gripper)
};

}  // namespace controller
}  // namespace armctl
