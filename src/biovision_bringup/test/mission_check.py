#!/usr/bin/python3
"""Waits for mission_director's mission.json and checks the find-and-return mission ran to a defined
outcome within the time limit: the target was taught and the mission started, the task manager's action
returned a result with its reason, and — when the action says it succeeded — the target was remembered
within 1 m of where it is and the robot is home. Found, returned and collisions are printed, not asserted:
on this machine a successful run is not reliable yet (1 success in 3 runs after the session-7 merges; the
mission figures over many rooms are mission_eval's, docs/benchmarks.md)."""
import sys
import unittest

import rospy
import rostest

from summary_wait import wait_for_summary


class Mission(unittest.TestCase):
    def test_the_mission_runs_to_a_defined_outcome(self):
        summary = wait_for_summary(rospy.get_param("~summary"), float(rospy.get_param("~timeout", 300.0)))
        self.assertIsNotNone(summary, "mission_director wrote no mission.json in time")
        print(f"mission: found {summary['found']}, returned {summary['returned']}, "
              f"collisions {summary['collisions']}: {summary['message']}")
        self.assertTrue(summary["mission_started"], summary)
        # The mission starts only once the shown target was recognised: those images count as teaching's.
        self.assertGreaterEqual(summary["recognitions_while_teaching"].get(summary["target"], 0), 1, summary)
        self.assertIsNotNone(summary["sim_duration_s"], summary)  # the action's result, not the director's time-out
        self.assertTrue(summary["message"], summary)
        if summary["success"]:
            self.assertTrue(summary["found"] and summary["returned"] and not summary["collisions"], summary)
            self.assertLess(summary["target_error_m"], 1.0, summary)


if __name__ == "__main__":
    rospy.init_node("mission_check")
    rostest.rosrun("biovision_bringup", "mission", Mission, sys.argv)
