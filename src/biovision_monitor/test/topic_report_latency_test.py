#!/usr/bin/python3
"""topic_report's header-stamp latency on raw (AnyMsg) messages: only types whose first field is a Header are
read, decided per type (a topic's publishers may change type), short buffers and zero stamps give no sample,
and a zero ROS time (sim time before /clock) is no arrival time."""
import importlib.machinery
import importlib.util
import os
import struct
import unittest

import rospy
import rostest

HERE = os.path.dirname(os.path.realpath(__file__))
_loader = importlib.machinery.SourceFileLoader("topic_report", os.path.join(HERE, "..", "scripts", "topic_report"))
_spec = importlib.util.spec_from_loader("topic_report", _loader)
topic_report = importlib.util.module_from_spec(_spec)
_loader.exec_module(topic_report)

STAMPED = ("sensor_msgs/Image", "# an image\nHeader header\nuint32 height\n")
STRING = ("std_msgs/String", "string data\n")


class Raw:
    """What rospy hands an AnyMsg callback: the raw buffer and the connection header."""

    def __init__(self, kind, buff):
        self._connection_header = {"type": kind[0], "message_definition": kind[1]}
        self._buff = buff


def header_bytes(stamp):
    return struct.pack("<III", 7, stamp.secs, stamp.nsecs) + struct.pack("<I", 3) + b"cam"


class TopicReportLatency(unittest.TestCase):
    def test_stamped_types_only_and_per_type(self):
        stats = topic_report.TopicStats("/t")
        stats.callback(Raw(STAMPED, header_bytes(rospy.get_rostime() - rospy.Duration(0.25))))
        self.assertEqual(len(stats.latencies), 1)
        self.assertGreater(stats.latencies[0], 0.2)
        self.assertLess(stats.latencies[0], 5.0)
        # The topic's type changes to one without a Header: its bytes are no stamp (once they were read as one).
        stats.callback(Raw(STRING, struct.pack("<I", 12) + b"hello world!"))
        self.assertEqual(len(stats.latencies), 1)
        # And back.
        stats.callback(Raw(STAMPED, header_bytes(rospy.get_rostime())))
        self.assertEqual(len(stats.latencies), 2)
        self.assertEqual(stats.count, 3)

    def test_constants_before_the_header_and_odd_buffers(self):
        stats = topic_report.TopicStats("/t")
        status = ("x/Status", "uint8 OK=0  # fine\nuint8 ERROR=2\nstd_msgs/Header header\nuint8 level\n")
        stats.callback(Raw(status, header_bytes(rospy.get_rostime())))
        self.assertEqual(len(stats.latencies), 1)
        stats.callback(Raw(STAMPED, b"\x01\x02\x03"))  # short
        stats.callback(Raw(STAMPED, b""))
        stats.callback(Raw(STAMPED, struct.pack("<III", 1, 0, 0)))  # zero stamp
        stats.callback(Raw(("x/Empty", ""), header_bytes(rospy.get_rostime())))
        self.assertEqual(len(stats.latencies), 1)
        self.assertEqual(stats.count, 5)
        lat = stats.latency_ms()
        self.assertEqual(lat["samples"], 1)


if __name__ == "__main__":
    rospy.init_node("topic_report_latency_test")
    rostest.rosrun("biovision_monitor", "topic_report_latency", TopicReportLatency)
