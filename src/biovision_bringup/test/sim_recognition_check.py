#!/usr/bin/python3
"""Waits until the teacher has taught objects and recognition has named them: at least 2 objects taught,
at least 20 correct labels over at least 2 objects, at most 5% wrong ones (another object where the box is:
1 of 60 in one of three runs on 2026-11-29, can_yellow named on another object — recognition has false
positives, the thesis's too, so zero made the test flaky) and at most 5% of boxes on no object (the
teacher's summary)."""
import sys
import unittest

import rospy
import rostest

from summary_wait import wait_for_summary


class SimRecognition(unittest.TestCase):
    def test_taught_objects_are_recognised_and_nothing_is_misnamed(self):
        def enough(s):
            named = [k for k, v in s["per_label"].items() if v["correct"] > 0]
            return len(s["taught"]) >= 2 and s["correct"] >= 20 and len(named) >= 2

        summary = wait_for_summary(rospy.get_param("~summary"), 120.0, enough) or {}
        self.assertTrue(summary, "the teacher wrote no summary")
        self.assertGreaterEqual(len(summary["taught"]), 2, summary)
        self.assertGreaterEqual(summary["correct"], 20, summary)
        self.assertGreaterEqual(len([k for k, v in summary["per_label"].items() if v["correct"] > 0]), 2, summary)
        self.assertLessEqual(summary["wrong"], 0.05 * summary["correct"], summary)
        self.assertLessEqual(summary["mislocated"], 0.05 * summary["correct"], summary)


if __name__ == "__main__":
    rospy.init_node("sim_recognition_check")
    rostest.rosrun("biovision_bringup", "sim_recognition", SimRecognition, sys.argv)
