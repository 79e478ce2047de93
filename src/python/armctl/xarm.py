"""A drop-in for scripts written for the ``xarm`` package (Controller, Servo, setPosition, ...).

Change the import line to ``import armctl.xarm as xarm`` and the script runs on armctl's Robot
Commands client: an xArm on USB (``'USB'``) or a serial port (``'/dev/ttyUSB0'``), the emulated
xArm (``'sim'``), armctl's SCARA arm controller, or any armctl board URI. The calls, their
argument forms and return values are that package's; where it misbehaves this module does the
right thing (docs/python.md "The xarm drop-in"):

- a reply is waited for only until it comes (that package waits out its full timeout on
  every USB reply), and a reply that never comes raises armctl.Error (kind 'timeout')
  instead of an empty result;
- ``servoOff()`` with no servos turns off every servo the board has, 7 on the SCARA arm
  controller (that package only ever turns off servos 1..6);
- angles map to positions as the xArm's servos turn: 0.24 degrees per unit, 500 at 0, so
  -120..120 degrees over 0..1000 (that package uses 0.25 degrees per unit, -125..125);
- ``getBatteryVoltage()`` raises armctl.Error when the board does not answer instead of
  returning 0.0 after five seconds of retries;
- ``getPosition([servo, ...])`` also returns the positions (that package returns None);
- ``setPosition(..., wait=True)`` returns when the servos are there (within one unit, as read
  back after the duration, for at most one second more), not merely when the time is up;
- a duration that is not an int 0..30000 ms is refused (that package sends its low 16 bits);
- ``setPosition`` refuses a servo ID the board does not have (a board ignores a move to it);
- one Controller can be used from several threads: each request and its reply take their turn
  on the link (that package lets them interleave and take each other's replies).

Integers may be any integral number (``numpy.int64(600)``, ``600.0`` where only units are
taken); bools are not numbers here.

Argument errors raise armctl.xarm.ArgumentError, which is both armctl.Error (kind
'invalid_argument') and ValueError, as that package's checks raise ValueError.
"""

import numbers as _numbers
import time as _time

from . import _armctl

__all__ = ["Controller", "Servo", "ArgumentError", "DEGREES_PER_UNIT"]

#: Degrees of servo rotation per position unit on the xArm's bus servos (0..1000 = 240 deg).
DEGREES_PER_UNIT = 0.24
_CENTRE = 500
_ANGLE_LIMIT = _CENTRE * DEGREES_PER_UNIT  # 120 deg
_SETTLED = 1  # units (0.24 deg): a servo this near its target has arrived
_SETTLE_SECONDS = 1.0


class ArgumentError(_armctl.Error, ValueError):
    """A call's argument is not allowed: armctl.Error (kind 'invalid_argument') and ValueError."""

    def __init__(self, message):
        super().__init__(message)
        self.kind = "invalid_argument"
        self.message = message


def _integer(value):
    """``value`` as an int when it is an integral number (an int, a NumPy integer, a float without
    a fraction such as 600.0), else None; a bool is not a number here (True is not servo 1)."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Real):  # numpy.bool_ is no Real
        return None
    if isinstance(value, _numbers.Integral):
        return int(value)
    value = float(value)
    return int(value) if value.is_integer() else None


def _is_units(value):
    """An integer type (int, NumPy integers): a position in units where an angle may also go."""
    return isinstance(value, _numbers.Integral) and not isinstance(value, bool)


def _is_angle(value):
    """Any other real number (float, NumPy floats): an angle in degrees where a position may also go."""
    return isinstance(value, _numbers.Real) and not isinstance(value, (bool, _numbers.Integral))


def _angle_to_position(angle):
    if not -_ANGLE_LIMIT <= angle <= _ANGLE_LIMIT:
        raise ArgumentError(
            f"angle {angle} deg is not allowed: -{_ANGLE_LIMIT:g}..{_ANGLE_LIMIT:g} deg"
            " (a float is an angle, an int a position 0..1000)")
    return int(round(_CENTRE + angle / DEGREES_PER_UNIT))


def _position_to_angle(position):
    return round((position - _CENTRE) * DEGREES_PER_UNIT, 2)


def _check_position(position):
    if not 0 <= position <= 1000:
        raise ArgumentError(
            f"position {position} is not allowed: 0..1000 (an int is a position, a float an angle in deg)")
    return position


def _units(position):
    """A position as that package takes it: an int in units, a float an angle in degrees."""
    if _is_units(position):
        return _check_position(int(position))
    if _is_angle(position):
        return _angle_to_position(float(position))
    raise ArgumentError(
        f"position {position!r} is not allowed: an int 0..1000 (units) or a float -120.0..120.0 (degrees)")


def _check_id(servo_id):
    sid = _integer(servo_id)
    if sid is None or not 1 <= sid <= 254:
        raise ArgumentError(f"servo ID {servo_id!r} is not allowed: an int 1..254")
    return sid


class Servo:
    """One servo's ID and position: ``Servo(servo_id, position=500)``.

    ``position`` is an int in units (0..1000) or a float angle in degrees (-120.0..120.0);
    setting either ``position`` or ``angle`` sets the other.
    """

    def __init__(self, servo_id, position=500):
        self.servo_id = _check_id(servo_id)
        self._position = _CENTRE
        if _is_angle(position):
            self.angle = position
        else:
            self.position = position

    @property
    def position(self):
        """Position in units, 0..1000."""
        return self._position

    @position.setter
    def position(self, value):
        units = _integer(value)
        if units is None:
            raise ArgumentError(f"position {value!r} is not allowed: an int 0..1000")
        self._position = _check_position(units)

    @property
    def angle(self):
        """Angle in degrees from the centre, 0.24 deg per unit."""
        return _position_to_angle(self._position)

    @angle.setter
    def angle(self, value):
        if isinstance(value, bool) or not isinstance(value, _numbers.Real):
            raise ArgumentError(f"angle {value!r} is not allowed: a number of degrees -120..120")
        self._position = _angle_to_position(float(value))

    def __repr__(self):
        return f"Servo({self.servo_id}, {self._position})"


def _device_uri(com_port, usb_path):
    if not isinstance(com_port, str) or not com_port:
        raise ArgumentError(f"com_port {com_port!r} is not allowed: 'USB', 'USB<serial>', a /dev path or an armctl URI")
    if com_port.startswith("USB"):
        serial = com_port[3:]
        if usb_path is not None:
            return "hid:" + usb_path
        return "hid:" + serial if serial else "hid"
    if com_port.upper().startswith("COM") and com_port[3:].isdigit():
        raise _armctl_error("unsupported",
                            f"com_port '{com_port}' is a Windows port; on Linux give the serial device, e.g. '/dev/ttyUSB0'")
    return com_port  # /dev/..., serial:..., hid..., sim: the URI armctl takes


def _armctl_error(kind, message):
    e = _armctl.Error(message)
    e.kind = kind
    e.message = message
    return e


def _ids(servos, what):
    """Servo IDs from an int, a Servo, or a list of them."""
    if _integer(servos) is not None:
        return [_check_id(servos)]
    if isinstance(servos, Servo):
        return [servos.servo_id]
    if isinstance(servos, (list, tuple)):
        out = []
        for s in servos:
            out.extend(_ids(s, what) if isinstance(s, Servo) or _integer(s) is not None else _bad(s, what))
        return out
    return _bad(servos, what)


def _bad(value, what):
    raise ArgumentError(f"{what} {value!r} is not allowed: a servo ID, a Servo, or a list of them")


class Controller:
    """A board: ``Controller(com_port, debug=False, usb_path=None)``.

    ``com_port``: ``'USB'`` (the first xArm on USB), ``'USB<serial number>'``, a serial device
    (``'/dev/ttyUSB0'``), or any armctl board URI (``'sim'``: an emulated xArm inside this
    process; ``'serial:/dev/ttyAMA0?baud=115200'``). ``usb_path``: a hidraw device
    (``'/dev/hidraw3'``). ``debug=True`` prints each call. Also ``servo_count`` (default 7:
    the SCARA arm controller's, which covers the xArm's 6) and ``timeout`` (s, 0: the link's).
    """

    def __init__(self, com_port, debug=False, usb_path=None, servo_count=7, timeout=0.0):
        self.debug = debug
        self.servos = []
        self._present = None
        self._answered = set()  # servo IDs that answered a read: the board has them
        self._client = _armctl.RobotCommands(_device_uri(com_port, usb_path), servo_count, timeout)

    def close(self):
        """Closes the board (an embedded one ends)."""
        self._client.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _log(self, text):
        if self.debug:
            print(text)

    def setPosition(self, servos, position=None, duration=1000, wait=False):
        """Moves servos over ``duration`` ms; ``wait=True`` returns after it.

        ``servos``: a servo ID (then ``position`` is required: an int in units 0..1000 or a
        float angle in degrees), a Servo (its position), or a list of Servos and
        ``[id, position]`` pairs.
        """
        ms = _integer(duration)
        if ms is None or not 0 <= ms <= 30000:
            raise ArgumentError(f"duration {duration!r} is not allowed: an int 0..30000 (ms)")
        duration = ms
        targets = []
        if _integer(servos) is not None:
            if position is None:
                raise ArgumentError("parameter 'position' missing: give a position (int) or an angle (float)")
            targets.append((_check_id(servos), _units(position)))
        elif isinstance(servos, Servo):
            targets.append((servos.servo_id, servos.position))
        elif isinstance(servos, (list, tuple)):
            for s in servos:
                if isinstance(s, Servo):
                    targets.append((s.servo_id, s.position))
                elif isinstance(s, (list, tuple)) and len(s) == 2 and _integer(s[0]) is not None:
                    targets.append((_check_id(s[0]), _units(s[1])))
                else:
                    raise ArgumentError(f"list entry {s!r} is not allowed: a Servo or an [id, position] pair")
        else:
            raise ArgumentError(f"servos {servos!r} is not allowed: a servo ID, a Servo, or a list")
        self._check_present([sid for sid, _ in targets])
        self._log(f"setPosition {targets} over {duration} ms")
        self._client.move(targets, duration)
        if wait:
            _time.sleep(duration / 1000)
            self._settle(targets)

    def _check_present(self, ids):
        # A board ignores a move to a servo it does not have: refuse it instead. IDs are
        # confirmed by reading them once (a few ms); only when that read gets no answer are the
        # board's servos looked up (_present_servos) to say which it has.
        unknown = [sid for sid in ids if sid not in self._answered]
        if not unknown:
            return
        try:
            self._client.read_positions(unknown)
            self._answered.update(unknown)
            return
        except _armctl.Error as e:
            if e.kind != "timeout":
                raise
        present = self._present_servos()
        missing = [sid for sid in ids if sid not in present]
        if missing:
            raise ArgumentError(
                f"servo ID {', '.join(map(str, missing))} is not allowed: the board has servos"
                f" {', '.join(map(str, present))}")
        self._answered.update(ids)

    def _settle(self, targets):
        # The board's time is when its interpolation ends; a servo under load arrives a little
        # later. Read until every servo is within _SETTLED units of its target (at most
        # _SETTLE_SECONDS more): wait=True then means "there", not "the time is up".
        deadline = _time.monotonic() + _SETTLE_SECONDS
        wanted = dict(targets)
        while True:
            read = dict(self._client.read_positions(list(wanted)))
            if all(abs(read[sid] - p) <= _SETTLED for sid, p in wanted.items()) or _time.monotonic() >= deadline:
                return
            _time.sleep(0.02)

    def getPosition(self, servos, degrees=False):
        """A servo's position in units (an int), or its angle in degrees with ``degrees=True``.

        A Servo is updated and its position (or angle) returned; a list of Servos (or IDs) is
        read in one request, each Servo updated, and the positions (or angles) returned.
        """
        if isinstance(servos, (list, tuple)):
            ids = _ids(servos, "servos")
            read = dict(self._client.read_positions(ids))
            out = []
            for s in servos:
                sid = s.servo_id if isinstance(s, Servo) else _check_id(s)
                value = read[sid]
                if isinstance(s, Servo):
                    s.position = min(max(value, 0), 1000)
                out.append(_position_to_angle(value) if degrees else value)
            return out
        sid = _ids(servos, "servos")[0]
        value = dict(self._client.read_positions([sid]))[sid]
        self._log(f"getPosition {sid}: {value}")
        if isinstance(servos, Servo):
            servos.position = min(max(value, 0), 1000)
        return _position_to_angle(value) if degrees else value

    def servoOff(self, servos=None):
        """Removes torque: from the listed servos, or (None) from every servo the board has."""
        ids = self._present_servos() if servos is None else _ids(servos, "servos")
        self._log(f"servoOff {ids}")
        self._client.servos_off(ids)

    def getBatteryVoltage(self):
        """The supply voltage in volts."""
        return self._client.battery_millivolts() / 1000.0

    def listServos(self, maximum_servo_id=6):
        """The servo IDs 1..maximum_servo_id that answer a position read (kept in ``servos``)."""
        maximum = _integer(maximum_servo_id)
        if maximum is None or not 1 <= maximum <= 254:
            raise ArgumentError(f"maximum_servo_id {maximum_servo_id!r} is not allowed: 1..254")
        maximum_servo_id = maximum
        found = []
        ids = list(range(1, maximum_servo_id + 1))
        try:  # one request when every servo is there (the usual case)
            found = [sid for sid, _ in self._client.read_positions(ids)]
        except _armctl.Error:
            for sid in ids:
                try:
                    self._client.read_positions([sid])
                    found.append(sid)
                except _armctl.Error:
                    pass
        self.servos = found
        self._log(f"Found {len(found)} servos: {found}")
        return self.servos

    def writeServoId(self, new_servo_id=0, overwrite_all_servo_ids=False):
        """Gives the servo on the bus the ID ``new_servo_id``; with more than one servo connected,
        only if ``overwrite_all_servo_ids`` (the command reaches every servo on the bus)."""
        new_id = _integer(new_servo_id)
        if new_id is None or not 1 <= new_id <= 254:
            raise ArgumentError(f"new_servo_id {new_servo_id!r} is not allowed: 1..254")
        new_servo_id = new_id
        if not overwrite_all_servo_ids:
            present = self.listServos(self._client.servo_count)
            if not present:
                raise _armctl_error("device", "no servo answers: nothing to renumber")
            if len(present) > 1:
                raise ArgumentError(
                    f"{len(present)} servos are connected ({present}): connect only the one to renumber,"
                    " or pass overwrite_all_servo_ids=True to give all of them the ID")
        self._client.write_servo_id(new_servo_id)

    def _present_servos(self):
        # Every servo the board has: the arm controller's 7, else the xArm's 6 (each read of an
        # absent servo costs a reply timeout, so the two usual sets are tried first).
        if self._present is None:
            for count in (self._client.servo_count, 6):
                try:
                    self._present = [sid for sid, _ in self._client.read_positions(list(range(1, count + 1)))]
                    break
                except _armctl.Error:
                    continue
            else:
                self._present = self.listServos(self._client.servo_count)
        return self._present
