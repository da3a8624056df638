#!/usr/bin/python3
"""The bad-input battery (issue #23): one rostest driver, parametrised per node by ~node.

For the node under test it feeds the kinds of bad input that node reads (bad calibration, bad joints,
non-finite and huge regions, big-endian and NaN images, oversized frames, a backward jump of ROS time) and
asserts for each: the node stays alive, nothing it publishes is non-finite or out of range, its
"errors since start" diagnostic grows with an ERROR status (one error per bad input, not just the
10 s hold of an earlier one), and its output resumes on good input. Oversized frames also check the node's
peak RSS (VmHWM from /proc). The launch file sets /use_sim_time; this driver publishes /clock itself so
that it can make time jump back.

~node: saliency | head_controller | base_controller | biobin_disparity | v1_cells | recognition | sim_tools |
topic_report
(sim_tools: still_camera and sim, and topic_report, started with bad parameters must exit with a message
naming the parameter and no traceback or crash). docs/reliability.md lists what each node is tested against.
"""
import math
import os
import random
import struct
import subprocess
import sys
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, JointState

NAN, INF = float("nan"), float("inf")
WIDTH, HEIGHT = 160, 120
BIG_W, BIG_H = 4000, 3000  # the oversized frame of issue #23 item 12


# ---------------------------------------------------------------- helpers


def finite(*values):
    return all(math.isfinite(v) for v in values)


def wait_for(condition, seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end and not rospy.is_shutdown():
        if condition():
            return True
        time.sleep(0.02)
    return condition()


def texture(seed, width=WIDTH, height=HEIGHT):
    """Grey levels [width*height] of smooth random blobs: V1 cells, BioBin and saliency all find structure."""
    rng = random.Random(seed)
    coarse_w, coarse_h = width // 8 + 2, height // 8 + 2
    coarse = [[rng.randint(0, 255) for _ in range(coarse_w)] for _ in range(coarse_h)]
    out = bytearray(width * height)
    for y in range(height):
        fy, ry = divmod(y, 8)
        for x in range(width):
            fx, rx = divmod(x, 8)
            a, b = coarse[fy][fx], coarse[fy][fx + 1]
            c, d = coarse[fy + 1][fx], coarse[fy + 1][fx + 1]
            top = a + (b - a) * rx / 8
            bottom = c + (d - c) * rx / 8
            out[y * width + x] = int(top + (bottom - top) * ry / 8)
    return out


def image(grey, encoding="mono8", width=WIDTH, height=HEIGHT, big_endian=False, stamp=None, frame="camera"):
    """An Image from 8-bit grey levels in the requested encoding and byte order."""
    m = Image(width=width, height=height, encoding=encoding, is_bigendian=1 if big_endian else 0)
    m.header.stamp = stamp if stamp is not None else rospy.Time.now()
    m.header.frame_id = frame
    order = ">" if big_endian else "<"
    if encoding in ("mono8", "8UC1"):
        m.step, m.data = width, bytes(grey)
    elif encoding == "bgr8":
        m.step, m.data = 3 * width, bytes(v for g in grey for v in (g, g, g))
    elif encoding in ("mono16", "16UC1"):
        m.step, m.data = 2 * width, struct.pack(order + "%dH" % len(grey), *(g * 257 for g in grey))
    elif encoding == "32FC1":
        m.step, m.data = 4 * width, struct.pack(order + "%df" % len(grey), *(g / 255.0 for g in grey))
    else:
        raise ValueError(encoding)
    return m


def float_image(values, width=WIDTH, height=HEIGHT):
    m = Image(width=width, height=height, encoding="32FC1", is_bigendian=0, step=4 * width)
    m.header.stamp = rospy.Time.now()
    m.header.frame_id = "camera"
    m.data = struct.pack("<%df" % len(values), *values)
    return m


def big_image(encoding="bgr8"):
    m = Image(width=BIG_W, height=BIG_H, encoding=encoding, is_bigendian=0, step=3 * BIG_W)
    m.header.stamp = rospy.Time.now()
    m.header.frame_id = "camera"
    m.data = bytes(3 * BIG_W * BIG_H)
    return m


def camera_info(fx=100.0, cx=80.0, cy=60.0, tx=0.0, width=WIDTH, height=HEIGHT, stamp=None, frame="camera"):
    info = CameraInfo(width=width, height=height, distortion_model="plumb_bob")
    info.header.stamp = stamp if stamp is not None else rospy.Time.now()
    info.header.frame_id = frame
    info.D = [0.0] * 5
    info.K = [fx, 0, cx, 0, fx, cy, 0, 0, 1]
    info.R = [1, 0, 0, 0, 1, 0, 0, 0, 1]
    info.P = [fx, 0, cx, tx, 0, fx, cy, 0, 0, 0, 1, 0]
    return info


def joints(pan, tilt):
    js = JointState(name=["head_pan_joint", "head_tilt_joint"], position=[pan, tilt])
    js.header.stamp = rospy.Time.now()
    return js


def node_pid(name):
    master = rosgraph.Master("/bad_input_battery")
    uri = master.lookupNode(name)
    code, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/bad_input_battery")
    return pid if code == 1 else None


def memory_kb(pid, key):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0


class SimClock:
    """Publishes /clock at 100 Hz of wall time (1 s of ROS time per wall second); jump_to() moves it."""

    def __init__(self, start=1000.0):
        self.now = start
        self.lock = threading.Lock()
        self.pub = rospy.Publisher("/clock", Clock, queue_size=10)
        threading.Thread(target=self.run, daemon=True).start()

    def run(self):
        while not rospy.is_shutdown():
            with self.lock:
                self.now += 0.01
                t = self.now
            try:
                self.pub.publish(Clock(clock=rospy.Time.from_sec(t)))
            except rospy.ROSException:  # shutting down
                return
            time.sleep(0.01)

    def jump_to(self, t):
        with self.lock:
            self.now = t


class Diagnostics:
    """The node's status from /diagnostics: levels seen and its "errors since start" / time-jump counts."""

    def __init__(self, status_name):
        self.name = status_name
        self.lock = threading.Lock()
        self.received = 0
        self.errors = 0
        self.jumps = 0
        self.error_levels = 0
        self.last_message = ""
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.callback, queue_size=50)

    def callback(self, msg):
        for s in msg.status:
            if self.name not in s.name:
                continue
            values = {kv.key: kv.value for kv in s.values}
            with self.lock:
                self.received += 1
                self.last_message = s.message
                self.errors = int(values.get("errors since start", self.errors))
                self.jumps = int(values.get("ROS time jumps back", self.jumps))
                if s.level >= DiagnosticStatus.ERROR:
                    self.error_levels += 1

    def snapshot(self):
        with self.lock:
            return self.received, self.errors, self.error_levels, self.jumps


class Probe:
    """Keeps every message of a topic."""

    def __init__(self, topic, cls):
        self.messages = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, cls, self.callback, queue_size=50)

    def callback(self, msg):
        with self.lock:
            self.messages.append(msg)

    def count(self):
        with self.lock:
            return len(self.messages)

    def since(self, n):
        with self.lock:
            return list(self.messages[n:])


# ---------------------------------------------------------------- the shared test case


class BadInputBattery(unittest.TestCase):
    node = None
    status = None

    @classmethod
    def setUpClass(cls):
        cls.node = rospy.get_param("~node")
        cls.node_name = rospy.get_param("~node_name", "/" + cls.node)
        cls.clock = SimClock() if rospy.get_param("/use_sim_time", False) else None
        cls.failures_seen = []

    # --- assertions every case shares

    def pid(self):
        return node_pid(self.node_name)

    def assert_alive(self, what):
        pid = self.pid()
        self.assertIsNotNone(pid, "%s: the node is gone from the master after %s" % (self.node_name, what))
        self.assertTrue(os.path.exists("/proc/%d" % pid), "%s died after %s" % (self.node_name, what))

    def expect_error(self, what, feed, seconds=6.0):
        """Runs feed() (the bad input, repeated until the error shows) and asserts a new counted error and an
        ERROR status."""
        _, errors_before, levels_before, _ = self.diag.snapshot()
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            feed()
            if wait_for(lambda: self.diag.snapshot()[1] > errors_before and self.diag.snapshot()[2] > levels_before,
                        0.5):
                break
        _, errors_after, levels_after, _ = self.diag.snapshot()
        self.assertGreater(errors_after, errors_before, "%s: no error counted in the diagnostics (last status: %r)"
                           % (what, self.diag.last_message))
        self.assertGreater(levels_after, levels_before, "%s: no ERROR diagnostic status" % what)
        self.assert_alive(what)

    def wait_connected(self, publishers, seconds=10.0):
        self.assertTrue(wait_for(lambda: all(p.get_num_connections() > 0 for p in publishers), seconds),
                        "the node never subscribed to %s" % [p.name for p in publishers])

    def check_peak_rss(self, what, feed, budget_mb):
        """Feeds the oversized frame; the node's peak RSS may grow by at most budget_mb."""
        pid = self.pid()
        before = memory_kb(pid, "VmHWM")
        start = time.monotonic()
        try:
            self.expect_error(what, feed, seconds=20.0)
        finally:
            time.sleep(0.5)
            grown = (memory_kb(pid, "VmHWM") - before) / 1024.0
            rospy.loginfo("bad_input_battery: %s: peak RSS %.0f -> %.0f MB (+%.0f MB) in %.1f s", what,
                          before / 1024.0, before / 1024.0 + grown, grown, time.monotonic() - start)
        self.assertLess(grown, budget_mb, "%s: peak RSS grew by %.0f MB (budget %d MB)" % (what, grown, budget_mb))

    def check_clock_jump(self, keep_output):
        """Time jumps back 90 s twice (a bag looping twice): each jump is counted, the diagnostics keep coming
        after each, and output resumes."""
        if self.clock is None:
            self.skipTest("needs /use_sim_time")  # every bad_input.test sets it
        wait_for(lambda: self.diag.snapshot()[0] > 0, 5.0)
        for loop in (1, 2):
            jumps = self.diag.snapshot()[3]
            self.clock.jump_to(self.clock.now - 90.0)
            self.assertTrue(wait_for(lambda: self.diag.snapshot()[3] > jumps, 5.0),
                            "loop %d: the 90 s backward jump of ROS time was not counted in the diagnostics" % loop)
            received = self.diag.snapshot()[0]
            self.assertTrue(wait_for(lambda: self.diag.snapshot()[0] >= received + 3, 6.0),
                            "loop %d: diagnostics stopped after ROS time jumped back" % loop)
            keep_output()


# ---------------------------------------------------------------- per node


class Saliency(BadInputBattery):
    def setUp(self):
        self.diag = Diagnostics("Saliency")
        from biovision_msgs.msg import SalientRegionArray
        self.regions_probe = Probe("saliency/regions", SalientRegionArray)
        self.image_pub = rospy.Publisher("camera/image", Image, queue_size=2)
        self.info_pub = rospy.Publisher("camera_info", CameraInfo, queue_size=2, latch=True)
        self.joint_pub = rospy.Publisher("joint_states", JointState, queue_size=5)
        self.wait_connected([self.image_pub, self.info_pub, self.joint_pub])
        self.frames = [texture(s) for s in range(4)]
        self.k = 0

    def frame(self):
        self.k += 1
        self.image_pub.publish(image(self.frames[self.k % 4], "bgr8"))
        time.sleep(0.1)

    def assert_regions_sane(self, since, what):
        for m in self.regions_probe.since(since):
            for r in m.regions:
                self.assertTrue(finite(r.pan, r.tilt, r.peak_saliency, r.mean_saliency),
                                "%s: a region with pan %r tilt %r left the node" % (what, r.pan, r.tilt))
                self.assertLessEqual(abs(r.pan), math.pi, "%s: region pan %r" % (what, r.pan))
                self.assertLessEqual(abs(r.tilt), math.pi, "%s: region tilt %r" % (what, r.tilt))

    def resumes(self, what):
        n = self.regions_probe.count()
        self.info_pub.publish(camera_info())
        self.joint_pub.publish(joints(0.1, 0.0))
        for _ in range(10):
            self.frame()
            if self.regions_probe.count() > n + 1:
                break
        self.assertTrue(wait_for(lambda: self.regions_probe.count() > n, 3.0), "%s: no regions on good input" % what)
        self.assert_regions_sane(n, what)

    def test_bad_calibration_joints_and_frames(self):
        self.resumes("good input")
        bad_infos = {
            "fx = 0": camera_info(fx=0.0),
            "fx = NaN": camera_info(fx=NAN),
            "fx = Inf": camera_info(fx=INF),
            "fx = 1e-9": camera_info(fx=1e-9),
            "NaN in P (cx)": camera_info(cx=NAN),
            "zero-width camera_info": camera_info(width=0),
        }
        for what, info in bad_infos.items():
            n = self.regions_probe.count()

            def feed(info=info):
                self.info_pub.publish(info)
                self.frame()

            self.expect_error(what, feed)
            self.assert_regions_sane(n, what)
            self.resumes(what)
        bad_joints = {
            "pan = 1e30 rad": joints(1e30, 0.0),
            "pan = NaN": joints(NAN, 0.0),
            "tilt = -Inf": joints(0.0, -INF),
            "mismatched name/position lengths": JointState(name=["head_pan_joint", "head_tilt_joint"], position=[0.2]),
        }
        for what, js in bad_joints.items():
            n = self.regions_probe.count()

            def feed(js=js):
                self.joint_pub.publish(js)
                self.frame()

            self.expect_error(what, feed)
            self.assert_regions_sane(n, what)
            self.resumes(what)

    def test_oversized_frame_is_refused_with_bounded_memory(self):
        self.resumes("good input")
        big = big_image()
        self.check_peak_rss("a 4000x3000 frame", lambda: self.image_pub.publish(big), budget_mb=200)
        self.resumes("a 4000x3000 frame")

    def test_time_jumping_back(self):
        self.resumes("good input")
        self.check_clock_jump(lambda: self.resumes("a backward jump of ROS time"))


class HeadController(BadInputBattery):
    def setUp(self):
        from biovision_msgs.msg import AttractorState, SalientRegionArray
        from biovision_msgs.srv import SetHeadMode
        from std_msgs.msg import Float64
        self.SalientRegionArray = SalientRegionArray
        self.diag = Diagnostics("head controller")
        self.commands = Probe("head_pan_joint/command", Float64)
        self.tilts = Probe("head_tilt_joint/command", Float64)
        self.states = Probe("attractor/head", AttractorState)
        self.region_pub = rospy.Publisher("saliency/regions", SalientRegionArray, queue_size=5)
        self.joint_pub = rospy.Publisher("joint_states", JointState, queue_size=5)
        self.info_pub = rospy.Publisher("camera_info", CameraInfo, queue_size=2)
        self.wait_connected([self.region_pub, self.joint_pub, self.info_pub])
        rospy.wait_for_service("head/set_mode", 10.0)
        self.set_mode = rospy.ServiceProxy("head/set_mode", SetHeadMode)
        self.pan = 0.0
        self.stop = False
        self.thread = threading.Thread(target=self.joint_loop, daemon=True)
        self.thread.start()  # the head reports where it is, following its commands like a servo

    def tearDown(self):
        self.stop = True
        self.thread.join()

    def joint_loop(self):
        while not self.stop and not rospy.is_shutdown():
            last = self.commands.since(max(0, self.commands.count() - 1))
            if last and math.isfinite(last[-1].data):
                self.pan += max(-0.05, min(0.05, last[-1].data - self.pan))
            self.joint_pub.publish(joints(self.pan, 0.0))
            time.sleep(0.05)

    def regions(self, pans, tilt=0.0, peak=1.0):
        from biovision_msgs.msg import SalientRegion
        msg = self.SalientRegionArray(image_width=WIDTH, image_height=HEIGHT)
        msg.header.stamp = rospy.Time.now()
        for i, pan in enumerate(pans):
            msg.regions.append(SalientRegion(rank=i, peak_saliency=peak, mean_saliency=peak / 2, area=1000,
                                             pan=pan, tilt=tilt))
        return msg

    def assert_commands_sane(self, since, what):
        for probe in (self.commands, self.tilts):
            for c in probe.since(since):
                self.assertTrue(math.isfinite(c.data), "%s: command %r sent" % (what, c.data))
                self.assertLessEqual(abs(c.data), math.pi, "%s: command %r beyond limits" % (what, c.data))
        for s in self.states.since(0):
            self.assertTrue(finite(s.rate, s.angle, *s.attraction, *s.repulsion, *s.forcelet),
                            "%s: attractor state with NaN/Inf" % what)

    def turns_to(self, target, what, seconds=8.0):
        """A valid region at `target` rad (inside the view) must pull the head at least halfway there (the freeze of
        issue #23 item 8 kept the rate at exactly 0)."""
        start = self.pan
        end = time.monotonic() + seconds
        while time.monotonic() < end and abs(self.pan - target) > abs(start - target) / 2:
            self.region_pub.publish(self.regions([target]))
            time.sleep(0.1)
        self.assertLess(abs(self.pan - target), abs(start - target) / 2,
                        "%s: the head stayed at %.3f rad (from %.3f), target %.3f" % (what, self.pan, start, target))

    def test_nan_region_cannot_freeze_the_attractor(self):
        self.assertTrue(wait_for(lambda: self.commands.count() > 5, 10.0), "no pan commands on good joint states")
        self.region_pub.publish(self.regions([NAN]))
        time.sleep(0.3)
        res = self.set_mode("track", "region:0")
        self.assertFalse(res.success, "track of a region with pan NaN was accepted: " + res.message)
        self.assertTrue(self.set_mode("explore", "").success)
        # The target on the other side: from a head already near 0.3 rad, "halfway" was under 2 mrad and explore's
        # own wandering failed it (CI: from 0.296 to 0.170).
        self.turns_to(-0.3 if self.pan > 0 else 0.3, "after NaN region, track, explore")
        self.assert_commands_sane(0, "NaN region then track")

    def test_bad_regions_joints_and_calibration(self):
        self.assertTrue(wait_for(lambda: self.commands.count() > 5, 10.0), "no pan commands on good joint states")
        self.assertTrue(wait_for(lambda: self.diag.snapshot()[0] > 0, 5.0), "no diagnostics at all")
        cases = {
            "a region with pan NaN": lambda: self.region_pub.publish(self.regions([NAN])),
            "a region with pan Inf": lambda: self.region_pub.publish(self.regions([INF])),
            "a region with pan 1e30": lambda: self.region_pub.publish(self.regions([1e30])),
            "a region with tilt NaN": lambda: self.region_pub.publish(self.regions([0.2], tilt=NAN)),
            "a 10,000-region message": lambda: self.region_pub.publish(self.regions([0.01 * (i % 50) for i in
                                                                                     range(10000)])),
            "joint_states with pan NaN": lambda: self.joint_pub.publish(joints(NAN, 0.0)),
            "joint_states with pan 1e30": lambda: self.joint_pub.publish(joints(1e30, 0.0)),
            "joint_states with mismatched lengths": lambda: self.joint_pub.publish(
                JointState(name=["head_pan_joint", "head_tilt_joint"], position=[0.1])),
            "a zero-width camera_info": lambda: self.info_pub.publish(camera_info(width=0)),
            "a camera_info with fx NaN": lambda: self.info_pub.publish(camera_info(fx=NAN)),
        }
        for what, feed in cases.items():
            n = self.commands.count()
            self.expect_error(what, feed)
            self.assert_commands_sane(n, what)
            self.region_pub.publish(self.regions([0.1]))
            self.assertTrue(wait_for(lambda: self.commands.count() > n + 5, 5.0),
                            "%s: no commands on good input afterwards" % what)
            self.assert_commands_sane(n, what)

    def test_time_jumping_back(self):
        self.assertTrue(wait_for(lambda: self.commands.count() > 5, 10.0), "no pan commands on good joint states")
        # The region on the side away from where the head is: a head already near it (after the first loop's
        # turn, or exploring) would have to move only a few hundredths of a radian, where its own inhibition
        # of return may hold it off.
        self.check_clock_jump(lambda: self.turns_to(-0.3 if self.pan > 0 else 0.3, "after a backward jump of ROS time"))


class BaseController(BadInputBattery):
    def setUp(self):
        from biovision_msgs.msg import EgoMap
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from std_msgs.msg import Float64
        self.EgoMap, self.Odometry, self.Float64 = EgoMap, Odometry, Float64
        self.diag = Diagnostics("base controller")
        self.cmds = Probe("cmd_vel", Twist)
        self.stm_pub = rospy.Publisher("memory/stm", EgoMap, queue_size=5)
        self.odom_pub = rospy.Publisher("odom", Odometry, queue_size=5)
        self.bearing_pub = rospy.Publisher("goal_bearing", Float64, queue_size=5)
        self.wait_connected([self.stm_pub, self.odom_pub, self.bearing_pub])
        self.bad_stm = None
        self.bad_odom = None
        self.stop = False
        self.thread = threading.Thread(target=self.world_loop, daemon=True)
        self.thread.start()  # fresh odometry and an empty short-term memory at 20 Hz

    def tearDown(self):
        self.stop = True
        self.thread.join()

    def stm(self, angles=None, distances=None):
        angles = [math.radians(a) for a in range(-80, 81, 20)] if angles is None else angles
        m = self.EgoMap(section_width=math.radians(20), section_angles=angles,
                        obstacle_distance=distances if distances is not None else [INF] * len(angles),
                        confidence=[1.0] * len(angles), max_range=3.0)
        m.header.stamp = rospy.Time.now()
        m.header.frame_id = "base_link"
        return m

    def odom(self, x=0.0):
        o = self.Odometry()
        o.header.stamp = rospy.Time.now()
        o.header.frame_id = "odom"
        o.pose.pose.position.x = x
        o.pose.pose.orientation.w = 1.0
        return o

    def world_loop(self):
        while not self.stop and not rospy.is_shutdown():
            self.stm_pub.publish(self.bad_stm or self.stm())
            self.odom_pub.publish(self.bad_odom or self.odom())
            time.sleep(0.05)

    def assert_commands_sane(self, since, what):
        for c in self.cmds.since(since):
            self.assertTrue(finite(c.linear.x, c.angular.z), "%s: cmd_vel %r" % (what, c))
            self.assertLessEqual(abs(c.linear.x), 0.5 + 1e-6, "%s: linear %r beyond max_linear" % (what, c.linear.x))
            self.assertLessEqual(abs(c.angular.z), 1.7453 + 1e-6, "%s: angular %r beyond max_angular" %
                                 (what, c.angular.z))

    def drives(self, what):
        n = self.cmds.count()
        moving = lambda: any(abs(c.angular.z) > 1e-3 or c.linear.x > 1e-3 for c in self.cmds.since(n))  # noqa: E731
        for _ in range(10):  # a bearing before the first odometry is refused: send it again
            self.bearing_pub.publish(self.Float64(0.3))
            if wait_for(moving, 0.5):
                break
        self.assertTrue(moving(), "%s: the base does not drive to a valid bearing" % what)
        self.assert_commands_sane(n, what)

    def test_bad_goals_odometry_and_memory(self):
        self.drives("good input")
        for what, bearing in (("goal_bearing NaN", NAN), ("goal_bearing 1e30", 1e30), ("goal_bearing -Inf", -INF)):
            n = self.cmds.count()
            self.expect_error(what, lambda bearing=bearing: self.bearing_pub.publish(self.Float64(bearing)))
            self.assert_commands_sane(n, what)
            self.drives("good input after " + what)
        nan_odom = self.odom()
        nan_odom.pose.pose.position.x = NAN
        short_offsets = self.stm()
        short_offsets.obstacle_offset = [0.5]
        cases = {"odom x NaN": ("odom", nan_odom),
                 "an STM angle NaN": ("stm", self.stm(angles=[NAN] * 9)),
                 "an STM angle 1e30": ("stm", self.stm(angles=[1e30] * 9)),
                 "an STM with mismatched arrays": ("stm", self.stm(distances=[1.0, 2.0])),
                 "an STM with mismatched obstacle_offset": ("stm", short_offsets)}
        for what, (kind, msg) in cases.items():
            n = self.cmds.count()

            def feed(kind=kind, msg=msg):
                if kind == "odom":
                    self.bad_odom = msg
                else:
                    self.bad_stm = msg

            self.expect_error(what, feed)
            self.bad_odom = self.bad_stm = None
            self.assert_commands_sane(n, what)
            self.drives("good input after " + what)


class BioBinDisparity(BadInputBattery):
    FX, BASELINE, TRUE_DISPARITY, CX_LEFT, CX_RIGHT = 100.0, 0.18, 8.0, 80.0, 74.0

    def setUp(self):
        from stereo_msgs.msg import DisparityImage
        self.diag = Diagnostics("BioBin disparity")
        self.disparities = Probe("stereo/disparity", DisparityImage)
        self.pubs = [rospy.Publisher("stereo/left/image_rect_color", Image, queue_size=2),
                     rospy.Publisher("stereo/left/camera_info", CameraInfo, queue_size=2),
                     rospy.Publisher("stereo/right/image_rect_color", Image, queue_size=2),
                     rospy.Publisher("stereo/right/camera_info", CameraInfo, queue_size=2)]
        self.wait_connected(self.pubs)
        # A fronto-parallel plane at Z = f T / 8 = 2.25 m: right pixel = left pixel - 8 - (cx_l - cx_r).
        wide = texture(7, WIDTH + 32, HEIGHT)
        shift = int(self.TRUE_DISPARITY + self.CX_LEFT - self.CX_RIGHT)
        self.left = bytearray(WIDTH * HEIGHT)
        self.right = bytearray(WIDTH * HEIGHT)
        for y in range(HEIGHT):
            row = wide[y * (WIDTH + 32):(y + 1) * (WIDTH + 32)]
            self.left[y * WIDTH:(y + 1) * WIDTH] = row[0:WIDTH]
            self.right[y * WIDTH:(y + 1) * WIDTH] = row[shift:shift + WIDTH]

    def pair(self, left_info=None, right_info=None, left=None, right=None):
        stamp = rospy.Time.now()
        li = left_info or camera_info(self.FX, self.CX_LEFT)
        ri = right_info or camera_info(self.FX, self.CX_RIGHT, tx=-self.FX * self.BASELINE)
        for m in (li, ri):
            m.header.stamp = stamp
        left = left or image(self.left, "bgr8")
        right = right or image(self.right, "bgr8")
        left.header.stamp = right.header.stamp = stamp
        left.header.frame_id = right.header.frame_id = "camera"
        for pub, m in zip(self.pubs, (left, li, right, ri)):
            pub.publish(m)
        time.sleep(0.3)

    def median_disparity(self, msg):
        values = struct.unpack(("<" if not msg.image.is_bigendian else ">") + "%df" % (msg.image.width *
                                                                                      msg.image.height),
                               bytes(msg.image.data))
        w = msg.image.width
        centre = [values[y * w + x] for y in range(20, msg.image.height - 20) for x in range(30, w - 30)]
        for v in values:
            self.assertTrue(math.isfinite(v), "a NaN/Inf disparity was published")
        valid = sorted(v for v in centre if v >= msg.min_disparity)
        self.assertGreater(len(valid), len(centre) // 2, "fewer than half the plane's pixels have a disparity")
        return valid[len(valid) // 2]

    def resumes(self, what):
        n = self.disparities.count()
        for _ in range(10):
            self.pair()
            if self.disparities.count() > n:
                break
        self.assertTrue(wait_for(lambda: self.disparities.count() > n, 5.0), "%s: no disparity on a good pair" % what)
        return self.disparities.since(n)[-1]

    def test_principal_points_that_differ_give_the_defined_disparity(self):
        msg = self.resumes("good pair")
        d = self.median_disparity(msg)
        z = msg.f * msg.T / d
        rospy.loginfo("bad_input_battery: cx 80/74, true disparity 8: median %.2f, Z = f T / d = %.2f m", d, z)
        self.assertAlmostEqual(d, self.TRUE_DISPARITY, delta=0.5,
                               msg="DisparityImage defines d = x_l - x_r - (cx_l - cx_r); got %.2f" % d)
        self.assertAlmostEqual(z, self.FX * self.BASELINE / self.TRUE_DISPARITY, delta=0.15)

    def test_bad_calibration_and_oversized_pairs(self):
        self.resumes("good pair")
        cases = {
            "left fx NaN": dict(left_info=camera_info(NAN, self.CX_LEFT)),
            "left fx 0": dict(left_info=camera_info(0.0, self.CX_LEFT)),
            "right fx 1e-9": dict(right_info=camera_info(1e-9, self.CX_RIGHT, tx=-1e-9 * self.BASELINE)),
            "a zero-width camera_info": dict(left_info=camera_info(self.FX, self.CX_LEFT, width=0)),
            "a 32FC1 image with NaN pixels": dict(left=float_image([NAN] * (WIDTH * HEIGHT)),
                                                  right=float_image([NAN] * (WIDTH * HEIGHT))),
        }
        for what, kwargs in cases.items():
            self.expect_error(what, lambda kwargs=kwargs: self.pair(**kwargs))
            self.resumes(what)
        big_info = camera_info(2000.0, BIG_W / 2, BIG_H / 2, width=BIG_W, height=BIG_H)
        big_right = camera_info(2000.0, BIG_W / 2, BIG_H / 2, tx=-2000.0 * self.BASELINE, width=BIG_W, height=BIG_H)
        big = big_image()
        self.check_peak_rss("a 4000x3000 pair", lambda: self.pair(big_info, big_right, big, big_image()),
                            budget_mb=400)
        self.resumes("a 4000x3000 pair")

    def test_time_jumping_back(self):
        self.resumes("good pair")
        self.check_clock_jump(lambda: self.resumes("a backward jump of ROS time"))


class V1Cells(BadInputBattery):
    def setUp(self):
        from biovision_msgs.msg import KeypointArray
        self.diag = Diagnostics("V1 cells")
        self.keypoints = Probe("keypoints", KeypointArray)
        self.image_pub = rospy.Publisher("camera/image", Image, queue_size=2)
        self.wait_connected([self.image_pub])
        self.grey = texture(3)

    def keypoints_of(self, msg, what):
        n = self.keypoints.count()
        for _ in range(10):
            self.image_pub.publish(msg)
            if wait_for(lambda: self.keypoints.count() > n, 1.0):
                break
        self.assertTrue(wait_for(lambda: self.keypoints.count() > n, 3.0), "%s: no keypoints message" % what)
        out = self.keypoints.since(n)[-1]
        for k in out.keypoints:
            self.assertTrue(finite(k.x, k.y, k.strength, k.orientation), "%s: a NaN/Inf keypoint" % what)
        return len(out.keypoints)

    def test_big_endian_images_decode_like_little_endian(self):
        reference = self.keypoints_of(image(self.grey, "mono8"), "mono8")
        self.assertGreater(reference, 5, "the test texture gives too few keypoints to compare")
        for encoding in ("mono16", "16UC1", "32FC1"):
            little = self.keypoints_of(image(self.grey, encoding), encoding + " little-endian")
            big = self.keypoints_of(image(self.grey, encoding, big_endian=True), encoding + " big-endian")
            self.assertEqual(big, little, "%s: %d keypoints big-endian, %d little-endian" % (encoding, big, little))

    def test_nan_pixels_and_oversized_frames(self):
        good = image(self.grey, "mono8")
        self.keypoints_of(good, "good input")
        values = [g / 255.0 for g in self.grey]
        for i in range(0, len(values), 7):
            values[i] = NAN if i % 2 else INF
        nan_image = float_image(values)
        self.expect_error("a 32FC1 image with NaN/Inf pixels", lambda: self.image_pub.publish(nan_image))
        self.keypoints_of(good, "good input after NaN pixels")
        big = big_image()
        self.check_peak_rss("a 4000x3000 frame", lambda: self.image_pub.publish(big), budget_mb=200)
        self.keypoints_of(good, "good input after a 4000x3000 frame")

    def test_time_jumping_back(self):
        good = image(self.grey, "mono8")
        self.keypoints_of(good, "good input")
        self.check_clock_jump(lambda: self.keypoints_of(image(self.grey, "mono8"), "after a backward jump"))


class Recognition(BadInputBattery):
    def setUp(self):
        from biovision_msgs.msg import RecognizedObjectArray
        self.diag = Diagnostics("Recognition")
        self.objects = Probe("objects", RecognizedObjectArray)
        self.image_pub = rospy.Publisher("camera/image", Image, queue_size=2)
        self.wait_connected([self.image_pub])
        self.grey = texture(5)

    def resumes(self, what):
        n = self.objects.count()
        for _ in range(10):
            self.image_pub.publish(image(self.grey, "bgr8"))
            if wait_for(lambda: self.objects.count() > n, 1.0):
                break
        self.assertTrue(wait_for(lambda: self.objects.count() > n, 3.0), "%s: no objects message" % what)
        for m in self.objects.since(n):
            for o in m.objects:
                self.assertTrue(finite(o.score, o.position.x, o.position.y, o.position.z), "%s: NaN/Inf object" % what)

    def test_nan_pixels_and_oversized_frames(self):
        self.resumes("good input")
        values = [NAN if i % 5 == 0 else g / 255.0 for i, g in enumerate(self.grey)]
        nan_image = float_image(values)
        self.expect_error("a 32FC1 image with NaN pixels", lambda: self.image_pub.publish(nan_image))
        self.resumes("a 32FC1 image with NaN pixels")
        big = big_image()
        self.check_peak_rss("a 4000x3000 frame", lambda: self.image_pub.publish(big), budget_mb=200)
        self.resumes("a 4000x3000 frame")

    def test_time_jumping_back(self):
        self.resumes("good input")
        self.check_clock_jump(lambda: self.resumes("a backward jump of ROS time"))


class Tools(BadInputBattery):
    """Nodes and scripts started with bad parameters exit at once, naming the parameter, without a traceback."""

    def setUp(self):
        self.diag = None

    runs = 0

    def run_tool(self, package, tool, params, words):
        # A fresh node name per run: private parameters of an earlier run stay on the parameter server.
        Tools.runs += 1
        args = ["rosrun", package, tool, "__name:=bad_params_%s_%d" % (tool, Tools.runs)] + \
            ["_%s:=%s" % kv for kv in params.items()]
        try:
            p = subprocess.run(args, capture_output=True, text=True, timeout=20)
        except subprocess.TimeoutExpired:
            self.fail("%s %s kept running with bad parameters %s" % (package, tool, params))
        out = p.stdout + p.stderr
        self.assertNotEqual(p.returncode, 0, "%s accepted %s:\n%s" % (tool, params, out[-2000:]))
        self.assertNotIn("Traceback", out, "%s printed a traceback for %s:\n%s" % (tool, params, out[-2000:]))
        self.assertNotIn("terminate called", out, "%s crashed for %s:\n%s" % (tool, params, out[-2000:]))
        self.assertIn(words, out, "%s: the message does not name %r for %s:\n%s" % (tool, words, params, out[-2000:]))


class SimTools(Tools):
    def test_still_camera_and_sim_refuse_bad_sizes(self):
        still = "/tmp/bad_input_battery_%d.pgm" % os.getpid()
        with open(still, "wb") as f:  # a 64x48 grey picture cv::imread reads
            f.write(b"P5 64 48 255\n" + bytes(texture(1, 64, 48)))
        world = rospy.get_param("~world")
        self.run_tool("biovision_sim", "still_camera", {"file": still, "width": 1000000000, "height": 100}, "width")
        self.run_tool("biovision_sim", "still_camera", {"file": still, "width": -5, "height": -5}, "width")
        self.run_tool("biovision_sim", "still_camera", {"file": still, "width": 64, "height": 0}, "height")
        self.run_tool("biovision_sim", "sim", {"world": world, "width": 1000000000, "publish_clock": "false"}, "width")
        self.run_tool("biovision_sim", "sim", {"world": world, "height": -240, "publish_clock": "false"}, "height")


class TopicReport(Tools):
    def test_topic_report_refuses_bad_parameters(self):
        ok = {"topics": "[/a, /b]", "duration": 0.5, "timeout": 0.5, "output": "/tmp/bad_input_battery_report"}
        for change, words in [({"duration": "abc"}, "~duration"),
                              ({"duration": -1}, "~duration"),
                              ({"frames": "[[a, b, c]]"}, "~frames"),
                              ({"frames": "[a]"}, "~frames"),
                              ({"topics": "/a"}, "~topics"),
                              ({"output": "/proc/no_such_folder/report"}, "~output")]:
            params = dict(ok)
            params.update(change)
            self.run_tool("biovision_monitor", "topic_report", params, words)


CASES = {"saliency": Saliency, "head_controller": HeadController, "base_controller": BaseController,
         "biobin_disparity": BioBinDisparity,
         "v1_cells": V1Cells, "recognition": Recognition, "sim_tools": SimTools, "topic_report": TopicReport}

if __name__ == "__main__":
    rospy.init_node("bad_input_battery")
    name = rospy.get_param("~node")
    rostest.rosrun("biovision_ros_common", "bad_input_" + name, CASES[name], sys.argv)
