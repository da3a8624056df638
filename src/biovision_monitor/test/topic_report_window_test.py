#!/usr/bin/python3
"""topic_report, run as the demo runs it, when its window never opens: ~start_topic sends nothing within
~timeout while another topic publishes. It must exit 1 with report.json saying the window never opened and
why (it once listened on after the timeout and reported a quiet, seemingly valid window), count what came
while waiting, and say so in report.md. With the start topic present the window opens and the run passes."""
import json
import os
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from std_msgs.msg import String


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

    def run_report(self, name):
        out = tempfile.mkdtemp(prefix="topic_report_window_")
        args = ["rosrun", "biovision_monitor", "topic_report", f"__name:={name}",
                "_topics:=['/window_test/chatter', '/window_test/start']",
                "_start_topic:=/window_test/start", "_timeout:=3.0", "_duration:=1.0", f"_output:={out}"]
        done = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60, text=True)
        with open(os.path.join(out, "report.json")) as f:
            report = json.load(f)
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


if __name__ == "__main__":
    rospy.init_node("topic_report_window_test")
    rostest.rosrun("biovision_monitor", "topic_report_window", TopicReportWindow)
