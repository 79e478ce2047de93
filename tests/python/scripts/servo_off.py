# In the style of the xarm package's README: torque off, in each form servoOff takes.
import sys

import armctl.xarm as xarm

arm = xarm.Controller(sys.argv[1] if len(sys.argv) > 1 else 'USB')
servo2 = xarm.Servo(2)
servo5 = xarm.Servo(5)
servo6 = xarm.Servo(6)

arm.servoOff(1)
arm.servoOff(servo2)
arm.servoOff([3, 4])
arm.servoOff([servo5, servo6])
arm.servoOff()
print('off:', arm.listServos(arm._client.servo_count))
