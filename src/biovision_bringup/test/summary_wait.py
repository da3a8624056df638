"""The wait shared by the rostest scripts that check a summary JSON written by a node under test."""
import json
import os
import time

import rospy


def wait_for_summary(path, timeout, done=None, poll=2.0):
    """Removes a previous run's `path`, then polls it every `poll` s for up to `timeout` s until it holds
    valid JSON and `done(summary)` (when given) is true. Returns the last summary read, or None."""
    if os.path.exists(path):
        os.remove(path)
    deadline = time.time() + timeout
    summary = None
    while time.time() < deadline and not rospy.is_shutdown():
        time.sleep(poll)
        try:
            with open(path) as f:
                summary = json.load(f)
        except (OSError, ValueError):
            continue
        if done is None or done(summary):
            break
    return summary
