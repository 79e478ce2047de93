# In the style of the xarm package's README: every form setPosition takes.
import sys

import armctl.xarm as xarm

arm = xarm.Controller(sys.argv[1] if len(sys.argv) > 1 else 'USB')

servo1 = xarm.Servo(1)       # position 500
servo2 = xarm.Servo(2, 300)  # unit position 300
servo3 = xarm.Servo(3, 90.0) # angle 90 degrees

arm.setPosition(1, 300, 400, wait=True)
print('servo 1:', arm.getPosition(1))
arm.setPosition(2, 700, 400, True)
print('servo 2:', arm.getPosition(2))
arm.setPosition(3, 45.0, 400, wait=True)
print('servo 3 (degrees):', arm.getPosition(3, degrees=True))
arm.setPosition(servo2, duration=400, wait=True)
print('servo 2:', arm.getPosition(servo2))
arm.setPosition([servo1, servo3], duration=400, wait=True)
print('servos 1, 3:', arm.getPosition([servo1, servo3]))
arm.setPosition([[1, 200], [2, 30.0]], 400, wait=True)
print('servo 1:', arm.getPosition(1), 'servo 2 (degrees):', arm.getPosition(2, True))
arm.setPosition([servo1, [2, 500], [3, 0.0]], duration=400, wait=True)
print('servos 1, 2, 3:', [arm.getPosition(s) for s in (1, 2, 3)])
