#!/usr/bin/python3
"""Checks what the perception graph makes of rosbags/tabletop_sweep.bag against golden values and the
simulator's ground truth recorded in the bag (tabletop_bag.launch).

- stereo/disparity (BioBin) against stereo/ground_truth/disparity of the same stamp, on the pixels where
  both are finite: per frame the median disparity, the median absolute error and the fraction off by
  more than 1 px (bad1); the run's figure is the median over frames;
- the head controller's first fixation: the first finite target of attractor/head [rad], and the
  labelled object nearest that direction (sim/objects);
- recognition's labels in `objects`: which labels were given, and each one's box centre must lie in the
  projected ground-truth box of that object at the message's stamp (tf + camera_info from the bag).

The run is over when, after data came, nothing new has arrived for ~quiet seconds (the player keeps
the bag's last clock). Every measured figure goes to ~result (JSON), whether the checks pass or not:
that is how the golden values were measured.
"""
import array
import json
import math
import statistics
import sys
import threading
import time
import unittest

import rospy
import rostest
import tf2_ros
from biovision_msgs.msg import AttractorState, RecognizedObjectArray
from sensor_msgs.msg import CameraInfo
from stereo_msgs.msg import DisparityImage
from visualization_msgs.msg import MarkerArray

PAN_AXIS_X = 0.05  # [m] the pan axis sits this far ahead of base_link (biovision_description)
IGNORED = {"table", "wall_back", "wall_left", "wall_right"}


def rotate(q, v):
    """Vector v rotated by unit quaternion q = (x, y, z, w)."""
    x, y, z, w = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def project_box(marker, transform, P):
    """(x, y, w, h) of the marker's corners in the image (as teach_from_bag), None if behind the camera."""
    t, q = transform.transform.translation, transform.transform.rotation
    o = marker.pose.orientation
    us, vs = [], []
    for sx in (-0.5, 0.5):
        for sy in (-0.5, 0.5):
            for sz in (-0.5, 0.5):
                c = rotate((o.x, o.y, o.z, o.w), (sx * marker.scale.x, sy * marker.scale.y, sz * marker.scale.z))
                p = (c[0] + marker.pose.position.x, c[1] + marker.pose.position.y, c[2] + marker.pose.position.z)
                p = rotate((q.x, q.y, q.z, q.w), p)
                p = (p[0] + t.x, p[1] + t.y, p[2] + t.z)
                if p[2] <= 0.05:
                    return None
                us.append(P[0] * p[0] / p[2] + P[2])
                vs.append(P[5] * p[1] / p[2] + P[6])
    return min(us), min(vs), max(us) - min(us), max(vs) - min(vs)


def floats(image):
    if image.encoding != "32FC1" or image.is_bigendian != (sys.byteorder == "big"):
        raise ValueError(f"disparity image is {image.encoding}, big-endian {image.is_bigendian}")
    data = array.array("f")
    data.frombytes(bytes(image.data))
    return data


def frame_figures(disparity, truth):
    """Median disparity, median |error| and bad1 on the pixels where both are finite, and BioBin's
    share of the ground truth's finite pixels."""
    d, g = floats(disparity.image), floats(truth.image)
    finite = [(a, b) for a, b in zip(d, g) if b > 0.0]
    both = [(a, b) for a, b in finite if a >= 0.0]
    if not both:
        return None
    errors = [abs(a - b) for a, b in both]
    return {"median": statistics.median(a for a, _ in both),
            "median_truth": statistics.median(b for _, b in both),
            "median_abs_error": statistics.median(errors),
            "bad1": sum(e > 1.0 for e in errors) / len(errors),
            "valid": len(both) / len(finite)}


class Recorder:
    def __init__(self):
        self.lock = threading.Lock()
        self.disparity, self.truth = {}, {}
        self.first_target = None
        self.objects = []  # (stamp, label, box centre)
        self.markers, self.info = [], None
        self.last_arrival = None
        self.buffer = tf2_ros.Buffer(rospy.Duration(60.0))
        self.listener = tf2_ros.TransformListener(self.buffer)
        rospy.Subscriber("stereo/disparity", DisparityImage, self.keep(self.disparity), queue_size=50)
        rospy.Subscriber("stereo/ground_truth/disparity", DisparityImage, self.keep(self.truth), queue_size=50)
        rospy.Subscriber("attractor/head", AttractorState, self.on_attractor, queue_size=50)
        rospy.Subscriber("objects", RecognizedObjectArray, self.on_objects, queue_size=50)
        rospy.Subscriber("sim/objects", MarkerArray, self.on_markers, queue_size=1)
        rospy.Subscriber("stereo/left/camera_info", CameraInfo, self.on_info, queue_size=1)

    def arrived(self):
        self.last_arrival = time.time()

    def keep(self, into):
        def callback(msg):
            with self.lock:
                into[msg.header.stamp.to_nsec()] = msg
                self.arrived()
        return callback

    def on_attractor(self, msg):
        with self.lock:
            if self.first_target is None and math.isfinite(msg.target):
                self.first_target = (msg.header.stamp.to_sec(), msg.target)

    def on_objects(self, msg):
        with self.lock:
            self.arrived()
            for o in msg.objects:
                centre = (o.box.x_offset + o.box.width / 2.0, o.box.y_offset + o.box.height / 2.0)
                self.objects.append((msg.header.stamp, o.label, centre))

    def on_markers(self, msg):
        with self.lock:
            self.markers = [m for m in msg.markers if m.ns not in IGNORED]

    def on_info(self, msg):
        with self.lock:
            self.info = msg


class TabletopBag(unittest.TestCase):
    def test_perception_of_the_committed_bag_matches_the_golden_values(self):
        quiet = float(rospy.get_param("~quiet", 6.0))
        rec = Recorder()
        deadline = time.time() + 130.0
        while time.time() < deadline and not rospy.is_shutdown():
            time.sleep(0.5)
            with rec.lock:
                if rec.last_arrival is not None and time.time() - rec.last_arrival > quiet:
                    break
        with rec.lock:
            figures = self.measure(rec)
        with open(rospy.get_param("~result"), "w") as f:
            json.dump(figures, f, indent=2)
        rospy.loginfo("tabletop_bag_check: %s", json.dumps(figures))
        self.check(figures)

    def measure(self, rec):
        frames = []
        for stamp, d in sorted(rec.disparity.items()):
            if stamp in rec.truth:
                f = frame_figures(d, rec.truth[stamp])
                if f:
                    frames.append(f)
        out = {"frames": len(frames), "ground_truth_frames": len(rec.truth),
               "per_frame": [{k: round(v, 4) for k, v in f.items()} for f in frames]}
        if frames:
            for k in ("median", "median_truth", "median_abs_error", "bad1", "valid"):
                out[k] = statistics.median(f[k] for f in frames)
            out["ground_truth_offset"] = abs(out["median"] - out["median_truth"])
        if rec.first_target:
            t, pan = rec.first_target
            out["first_fixation"] = {"t": t, "pan": pan}
            directions = [(m.ns, math.atan2(m.pose.position.y, m.pose.position.x - PAN_AXIS_X)) for m in rec.markers]
            if directions:
                out["first_fixation"]["object"] = min(directions, key=lambda o: abs(o[1] - pan))[0]
        given, right, wrong, unplaced = {}, 0, [], 0
        for stamp, label, (cx, cy) in rec.objects:
            given[label] = given.get(label, 0) + 1
            try:
                tf = rec.buffer.lookup_transform("stereo_left_optical", "map", stamp)
            except tf2_ros.TransformException:
                unplaced += 1
                continue
            hits = set()
            for m in rec.markers:
                box = project_box(m, tf, rec.info.P) if rec.info else None
                if box and box[0] <= cx <= box[0] + box[2] and box[1] <= cy <= box[1] + box[3]:
                    hits.add(m.ns)
            if label in hits:
                right += 1
            else:
                wrong.append({"t": stamp.to_sec(), "said": label, "there": sorted(hits)})
        out["labels"] = {"given": given, "right": right, "wrong": wrong, "no_tf": unplaced}
        return out

    def check(self, figures):
        def golden(name):
            return rospy.get_param("~" + name)
        self.assertGreaterEqual(figures["frames"], golden("frames/min"), "BioBin disparity frames scored")
        self.assertAlmostEqual(figures["median"], golden("median_disparity/value"),
                               delta=golden("median_disparity/tolerance"), msg="median disparity [px]")
        self.assertLessEqual(figures["ground_truth_offset"], golden("ground_truth_offset/max"),
                             "median disparity against the ground truth's [px]")
        self.assertLessEqual(figures["median_abs_error"], golden("median_abs_error/max"), "median |error| [px]")
        self.assertAlmostEqual(figures["bad1"], golden("bad1/value"), delta=golden("bad1/tolerance"), msg="bad1")
        self.assertAlmostEqual(figures["valid"], golden("valid/value"), delta=golden("valid/tolerance"),
                               msg="valid fraction")
        self.assertIn("first_fixation", figures, "the head controller chose no target")
        self.assertAlmostEqual(figures["first_fixation"]["pan"], golden("first_fixation/pan"),
                               delta=golden("first_fixation/tolerance"), msg="first fixation's pan [rad]")
        self.assertEqual(figures["first_fixation"].get("object"), golden("first_fixation/object"))
        labels = figures["labels"]
        self.assertEqual(sorted(labels["given"]), sorted(golden("labels/given")), "labels given")
        for label, n in labels["given"].items():
            self.assertGreaterEqual(n, golden("labels/min_each"), f"times '{label}' was given")
        self.assertEqual(labels["wrong"], [], "labels whose box is not on that object")
        self.assertEqual(labels["no_tf"], 0, "labels that could not be placed in tf")


if __name__ == "__main__":
    rospy.init_node("tabletop_bag_check")
    rostest.rosrun("biovision_bringup", "tabletop_bag_check", TabletopBag, sys.argv)
