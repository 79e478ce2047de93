# In the style of the xarm package's README: connect, read the battery and positions.
import sys

import armctl.xarm as xarm

arm = xarm.Controller(sys.argv[1] if len(sys.argv) > 1 else 'USB')
print('Battery voltage in volts:', arm.getBatteryVoltage())

servo1 = xarm.Servo(1)
servo2 = xarm.Servo(2)
servo3 = xarm.Servo(3)

position = arm.getPosition(1)
print('Servo 1 position:', position)
position = arm.getPosition(servo2)
print('Servo 2 position:', position)
position = arm.getPosition(3, True)
print('Servo 3 position (degrees):', position)
arm.getPosition([servo1, servo2, servo3])
print('Servo 1 position (degrees):', servo1.angle)
print('Servo 2 position (degrees):', servo2.angle)
print('Servo 3 position (degrees):', servo3.angle)
print('Servos:', arm.listServos())
