#!/usr/bin/python3
"""topic_report, run as the demo runs it, when its window never opens: ~start_topic sends nothing within
~timeout while another topic publishes. It must exit 1 with report.json saying the window never opened and
why (it once listened on after the timeout and reported a quiet, seemingly valid window), count what came
while waiting, and say so in report.md. With the start topic present the window opens and the run passes.
Also what a breaker found on 2026-12-07: a start topic sent once must count, a run shut down mid-window must
say how long it really listened, an earlier run's report must be gone before this run's window, and a NaN
transform must fail its pair in valid JSON."""
import json
import math
import os
import signal
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped
from std_msgs.msg import String


def strict_json(path):
    """report.json parsed as JSON is defined: NaN and Infinity are refused (Python's json accepts them)."""
    def refuse(constant):
        raise ValueError(f"{path}: {constant} is not JSON")
    with open(path) as f:
        return json.load(f, parse_constant=refuse)


class TopicReportWindow(unittest.TestCase):
    def setUp(self):
        self.pub = rospy.Publisher("/window_test/chatter", String, queue_size=10)
        self.start_pub = rospy.Publisher("/window_test/start", String, queue_size=10)
        self.stop = threading.Event()
        self.send_start = False
        self.thread = threading.Thread(target=self._publish, daemon=True)
        self.thread.start()

    def tearDown(self):
        self.stop.set()
        self.thread.join()

    def _publish(self):
        while not self.stop.is_set():
            self.pub.publish(String("x"))
            if self.send_start:
                self.start_pub.publish(String("go"))
            time.sleep(0.05)

    def command(self, name, out, extra=()):
        return ["rosrun", "biovision_monitor", "topic_report", f"__name:={name}",
                "_topics:=['/window_test/chatter', '/window_test/start']",
                "_start_topic:=/window_test/start", "_timeout:=3.0", "_duration:=1.0", f"_output:={out}",
                *extra]

    def run_report(self, name, extra=()):
        out = tempfile.mkdtemp(prefix="topic_report_window_")
        done = subprocess.run(self.command(name, out, extra), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=60, text=True)
        report = strict_json(os.path.join(out, "report.json"))
        with open(os.path.join(out, "report.md")) as f:
            markdown = f.read()
        return done, report, markdown

    def test_start_topic_never_came(self):
        done, report, markdown = self.run_report("report_never")
        self.assertEqual(done.returncode, 1, done.stdout)
        self.assertFalse(report["ok"])
        self.assertFalse(report["window"]["opened"])
        self.assertEqual(report["window"]["start_topic"], "/window_test/start")
        self.assertIn("/window_test/start sent nothing within 3 s", report["window"]["problem"])
        self.assertGreater(report["topics"]["/window_test/chatter"]["messages"], 10)  # what came while waiting
        self.assertEqual(report["topics"]["/window_test/start"]["messages"], 0)
        self.assertGreaterEqual(report["listened_s"], 2.9)
        self.assertIn("never opened", markdown)
        self.assertIn("never opened", done.stdout)

    def test_start_topic_opens_the_window(self):
        self.send_start = True
        done, report, _ = self.run_report("report_opened")
        self.assertEqual(done.returncode, 0, done.stdout)
        self.assertTrue(report["ok"])
        self.assertTrue(report["window"]["opened"])
        self.assertNotIn("problem", report["window"])
        self.assertGreater(report["topics"]["/window_test/start"]["messages"], 5)


    def test_a_start_topic_sent_once_is_counted(self):
        # mission.launch opens the window at the first goal, which may be the only one.
        out = tempfile.mkdtemp(prefix="topic_report_window_")
        proc = subprocess.Popen(self.command("report_once", out), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        deadline = time.monotonic() + 20
        while self.start_pub.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertGreater(self.start_pub.get_num_connections(), 0, "topic_report never subscribed")
        time.sleep(0.3)
        self.start_pub.publish(String("go"))
        stdout, _ = proc.communicate(timeout=60)
        report = strict_json(os.path.join(out, "report.json"))
        self.assertEqual(proc.returncode, 0, stdout)
        self.assertTrue(report["window"]["opened"])
        self.assertEqual(report["topics"]["/window_test/start"]["messages"], 1)
        self.assertGreater(report["topics"]["/window_test/chatter"]["messages"], 5)

    def test_shut_down_mid_window_says_how_long_it_listened(self):
        out = tempfile.mkdtemp(prefix="topic_report_window_")
        self.send_start = True
        proc = subprocess.Popen(self.command("report_interrupted", out, ["_duration:=60.0"]),
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        time.sleep(6.0)  # start-up (~2 s) and a few seconds of the 60 s window
        proc.send_signal(signal.SIGINT)
        stdout, _ = proc.communicate(timeout=30)
        report = strict_json(os.path.join(out, "report.json"))
        self.assertTrue(report["window"]["opened"], stdout)
        self.assertTrue(report["window"].get("interrupted"), report["window"])
        self.assertGreater(report["listened_s"], 0.5)
        self.assertLess(report["listened_s"], 10.0)  # never the 60 s it was asked for
        with open(os.path.join(out, "report.md")) as f:
            self.assertIn("shut down early", f.read())

    def test_an_earlier_report_is_gone_before_the_window(self):
        out = tempfile.mkdtemp(prefix="topic_report_window_")
        for name in ("report.json", "report.md"):
            with open(os.path.join(out, name), "w") as f:
                f.write('{"ok": true}\n')  # an earlier run's verdict
        proc = subprocess.Popen(self.command("report_killed", out, ["_timeout:=30.0"]), stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        deadline = time.monotonic() + 20
        while os.path.exists(os.path.join(out, "report.json")) and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertIsNone(proc.poll())  # still waiting for its window
        proc.kill()  # dies before writing: no report at all, not the old one
        proc.communicate(timeout=30)
        self.assertFalse(os.path.exists(os.path.join(out, "report.json")))
        self.assertFalse(os.path.exists(os.path.join(out, "report.md")))

    def test_a_nan_transform_fails_its_pair_in_valid_json(self):
        self.send_start = True
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = "window_test_parent"
        t.child_frame_id = "window_test_child"
        t.transform.translation.x = math.inf
        t.transform.rotation.w = 1.0
        broadcaster = tf2_ros.StaticTransformBroadcaster()
        broadcaster.sendTransform(t)
        done, report, markdown = self.run_report("report_nan",
                                                 ["_frames:=[[window_test_parent, window_test_child]]"])
        self.assertEqual(done.returncode, 1, done.stdout)
        self.assertFalse(report["ok"])
        self.assertEqual(len(report["frames"]), 1)
        self.assertFalse(report["frames"][0]["ok"])
        self.assertIn("not finite", report["frames"][0]["error"])
        self.assertIn("frames not resolved: window_test_parent -> window_test_child", markdown)

if __name__ == "__main__":
    rospy.init_node("topic_report_window_test")
    rostest.rosrun("biovision_monitor", "topic_report_window", TopicReportWindow)
