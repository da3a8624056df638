#!/usr/bin/python3
"""Waits for mission_director's mission.json and checks the find-and-return mission: the action
succeeded, the target was found and remembered within 1 m of where it is, the robot came back within
the director's home tolerance, and it hit nothing."""
import json
import os
import sys
import time
import unittest

import rospy
import rostest


class Mission(unittest.TestCase):
    def test_the_robot_finds_the_object_and_returns_home_without_collisions(self):
        path = rospy.get_param("~summary")
        if os.path.exists(path):
            os.remove(path)  # a previous run's
        deadline = time.time() + float(rospy.get_param("~timeout", 300.0))
        summary = None
        while summary is None and time.time() < deadline and not rospy.is_shutdown():
            time.sleep(2.0)
            try:
                with open(path) as f:
                    summary = json.load(f)
            except (OSError, ValueError):
                pass
        self.assertIsNotNone(summary, "mission_director wrote no mission.json in time")
        self.assertTrue(summary["success"], summary)
        self.assertTrue(summary["found"], summary)
        self.assertLess(summary["target_error_m"], 1.0, summary)
        self.assertTrue(summary["returned"], summary)
        self.assertEqual(summary["collisions"], [], summary)


if __name__ == "__main__":
    rospy.init_node("mission_check")
    rostest.rosrun("biovision_bringup", "mission", Mission, sys.argv)
