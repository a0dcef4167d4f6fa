#!/usr/bin/python3
"""pcl_ncut_seg rostest: a stream (stream.test). 300 clouds with their ~indices at a steady
rate: three in five are real views (the mesh sampler's depth views in their camera's frame,
organized with the object's pixels as indices or cropped, and PCL's milk and bunny scans from
the shared data), two in five are bad, of nine kinds. The node must answer every view with the
tool's labels, log every bad cloud once with what was wrong and publish nothing for it, keep
running, and keep its memory. The figures are printed at the end."""
import math
import os
import re
import shutil
import statistics
import struct
import sys
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from pcl_msgs.msg import PointIndices
from sensor_msgs.msg import PointField
from std_msgs.msg import Header

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcd_support import (camera_view, cli_labels, cloud_msg, finite, float32,  # noqa: E402
                         output_labels, shared_data, write_pcd)
from ros_test_support import (Log, PointCloud2, Stamps, String, node_pid,  # noqa: E402
                              report, resident_kib, stats, wait_for_connection,
                              wait_for_log_connection)

NODE = "/seg_stream"
PERIOD = 0.1  # seconds between two clouds
AHEAD = 4  # clouds neither answered nor logged yet, beyond which the publisher waits
STALL = 60.0  # seconds without a word from the node: it has stopped
MEMORY_SLACK_KIB = 4096
NAN = float("nan")


class Cloud:
    """A cloud of the stream: its message (restamped when sent), its indices, and either the
    tool's labels (a view) or the words the node's error must hold (a bad cloud)."""

    def __init__(self, kind, msg, indices, labels=None, reason=None):
        self.kind, self.msg, self.indices = kind, msg, list(indices)
        self.labels, self.reason = labels, reason

    def stamped(self, stamp):
        msg = PointCloud2(header=Header(stamp=stamp, frame_id=self.msg.header.frame_id))
        for slot in ("height", "width", "fields", "is_bigendian", "point_step", "row_step",
                     "data", "is_dense"):
            setattr(msg, slot, getattr(self.msg, slot))
        return msg


def views(data, work):
    """The real views, each with the tool's labels for the same points; and a frame's Pcd and
    a crop's points to make bad clouds of."""
    out, pcds = [], []
    for model, seed, organized in (("bunny", 1, True), ("horse", 2, False),
                                   ("cgal-hand", 3, True), ("santa", 4, False)):
        path, pcd = camera_view(model, seed, "320x240", work)
        pcds.append(pcd)
        if organized:  # a camera's frame, the object's pixels as indices
            labels, _ = cli_labels(path, work)
            indices = [i for i, p in enumerate(pcd.points) if all(map(math.isfinite, p))]
            msg = cloud_msg(pcd.points, rospy.Time(), "camera", pcd.width, pcd.height)
        else:  # the crop a tabletop pipeline hands over
            crop = finite(pcd.points)
            write_pcd(path, crop, len(crop))
            labels, _ = cli_labels(path, work)
            indices = range(len(crop))
            msg = cloud_msg(crop, rospy.Time(), "camera")
        out.append(Cloud("%s view %d" % (model, seed), msg, indices, labels))
    for name in ("milk", "bun0"):  # PCL's scans, as the tool reads them
        labels, pcd = cli_labels(os.path.join(data, "pcl", name + ".pcd"), work)
        xyz = [p[:3] for p in pcd.points]
        out.append(Cloud(name, cloud_msg(xyz, rospy.Time(), "camera"), range(len(xyz)), labels))
    return out, pcds[0], finite(pcds[1].points)


def packed(xyz, fields, codes):
    """A cloud of fields packed with the struct codes (one point a tuple)."""
    msg = cloud_msg([], rospy.Time(), "camera")
    msg.width, msg.fields = len(xyz), fields
    msg.point_step = struct.calcsize("<" + codes)
    msg.row_step = msg.point_step * msg.width
    msg.data = b"".join(struct.pack("<" + codes, *p) for p in xyz)
    return msg


def bad_kinds(crop, frame):
    """Per kind, the words its error must hold and its variants, from a crop and a frame."""
    f32 = PointField.FLOAT32
    huge = list(crop)
    huge[7] = (1e30, 0.0, 0.0)
    frame_indices = [i for i, p in enumerate(frame.points) if all(map(math.isfinite, p))]
    short_rows, long_rows = (cloud_msg(frame.points, rospy.Time(), "camera", frame.width,
                                       frame.height) for _ in range(2))
    short_rows.row_step -= 12  # rows overlap
    long_rows.row_step += 4  # rows beyond the data
    cloud = lambda xyz: (cloud_msg(xyz, rospy.Time(), "camera"), range(len(xyz)))  # noqa: E731
    empty = cloud_msg([], rospy.Time(), "camera")
    empty.height = 0
    return [
        ("empty", "the cloud is empty", [cloud([]), (empty, [])]),
        ("all NaN", "no finite point",
         [cloud([(NAN, NAN, NAN)] * 500),
          (cloud_msg([(NAN, NAN, NAN)] * len(frame.points), rospy.Time(), "camera",
                     frame.width, frame.height), range(len(frame.points)))]),
        ("1-3 points", "distinct finite point", [cloud(crop[:n]) for n in (1, 2, 3)]),
        ("duplicates", "distinct finite point", [cloud(crop[:1] * 500), cloud(crop[:2] * 300)]),
        ("huge coordinates", "beyond",
         [cloud(huge), cloud(float32([(p[0] + 3e7, p[1], p[2]) for p in crop]))]),
        ("no z", "no field z", [(packed([p[:2] for p in crop], [
            PointField("x", 0, f32, 1), PointField("y", 4, f32, 1)], "2f"), range(len(crop)))]),
        ("x FLOAT64", "field x is not one FLOAT32", [(packed(crop, [
            PointField("x", 0, PointField.FLOAT64, 1), PointField("y", 8, f32, 1),
            PointField("z", 12, f32, 1)], "d2f"), range(len(crop)))]),
        ("wrong row_step", "does not match its layout",
         [(short_rows, frame_indices), (long_rows, frame_indices)]),
        ("indices out of range", "out of range for a cloud of",
         [(cloud(crop)[0], list(range(len(crop))) + [len(crop)]),
          (cloud(crop)[0], [-1] + list(range(len(crop))))]),
    ]


def stream(good, kinds, clouds, checkpoint):
    """The clouds: two in five bad, the kinds in turn; the same view before each reading of
    the memory (the node keeps the last cloud)."""
    out, v, b = [], 0, 0
    for i in range(clouds):
        if i in (checkpoint - 1, clouds - 1):
            out.append(good[0])
        elif i % 5 in (1, 3):
            kind, reason, variants = kinds[b % len(kinds)]
            msg, indices = variants[(b // len(kinds)) % len(variants)]
            out.append(Cloud(kind, msg, indices, reason=reason))
            b += 1
        else:
            out.append(good[v % len(good)])
            v += 1
    return out


class Watch:
    """What the node said about each stamp (whole seconds: the stream's are 1 s apart): its
    labelled clouds (arrival, labels) and its log lines (level, text)."""

    LINE = re.compile(r" at (\d+)\.\d+ not segmented: ")

    def __init__(self):
        self.lock = threading.Condition()
        self.answers, self.logs, self.other_errors, self.seconds = {}, {}, [], {}
        rospy.Subscriber(NODE + "/output", PointCloud2, self._answer, queue_size=50)
        rospy.Subscriber(NODE + "/stats", String, self._stats, queue_size=50)
        rospy.Subscriber("/rosout", Log, self._log, queue_size=500)

    def _stats(self, msg):
        s = stats(msg)
        with self.lock:
            self.seconds[int(s["stamp"])] = s["analysis_seconds"] + s["cut_seconds"]

    def _answer(self, msg):
        labels = output_labels(msg)  # not the message: some MB each
        with self.lock:
            self.answers.setdefault(msg.header.stamp.secs, []).append((time.monotonic(), labels))
            self.lock.notify_all()

    def _log(self, msg):
        if msg.name != NODE:
            return
        match = self.LINE.search(msg.msg)
        with self.lock:
            if match:
                self.logs.setdefault(int(match.group(1)), []).append((msg.level, msg.msg))
            elif msg.level >= Log.ERROR:
                self.other_errors.append(msg.msg)
            self.lock.notify_all()

    def _pending(self, secs):
        return sum(1 for s in secs if s not in self.answers and s not in self.logs)

    def wait_done(self, secs, at_most):
        """Wait until at most at_most of the stamps have neither an answer nor a log line;
        False when the node says nothing for STALL seconds before."""
        with self.lock:
            pending = self._pending(secs)
            deadline = time.monotonic() + STALL
            while pending > at_most and time.monotonic() < deadline:
                self.lock.wait(0.05)
                if self._pending(secs) < pending:  # progress: a new deadline
                    pending, deadline = self._pending(secs), time.monotonic() + STALL
            return pending <= at_most

    def pending(self, secs):
        with self.lock:
            return self._pending(secs)


def spread(seconds):
    """"median M s, 95th percentile P s" (the nearest rank), or "none"."""
    if not seconds:
        return "none"
    ordered = sorted(seconds)
    p95 = ordered[max(0, math.ceil(0.95 * len(ordered)) - 1)]
    return "median %.3f s, 95th percentile %.3f s" % (statistics.median(ordered), p95)


class StreamTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("stream_test")
        cls.data = shared_data()
        if not cls.data:
            return
        cls.work = tempfile.mkdtemp(prefix="pcl_ncut_seg_stream_")
        cls.good, frame, crop = views(cls.data, cls.work)
        cls.kinds = bad_kinds(crop, frame)
        cls.watch = Watch()
        cls.clouds = rospy.Publisher(NODE + "/input", PointCloud2, queue_size=50)
        cls.indices = rospy.Publisher(NODE + "/indices", PointIndices, queue_size=50)
        assert wait_for_connection(cls.clouds) and wait_for_connection(cls.indices), \
            "the node did not subscribe to ~input and ~indices"
        assert wait_for_log_connection(NODE), "no /rosout connection from the node"
        cls.pid = node_pid(NODE)

    @classmethod
    def tearDownClass(cls):
        if cls.data:
            shutil.rmtree(cls.work, ignore_errors=True)

    def setUp(self):
        if not self.data:
            self.skipTest("the shared data (../shared/data, PCL_NCUT_SEG_SHARED_DATA) is absent")

    def send(self, cloud, stamp):
        header = Header(stamp=stamp, frame_id=cloud.msg.header.frame_id)
        self.indices.publish(PointIndices(header=header, indices=cloud.indices))
        self.clouds.publish(cloud.stamped(stamp))

    def test_stream_of_views_and_bad_clouds(self):
        watch, stamps = self.watch, Stamps()
        first = stamps()  # not counted: the node's first answer
        self.send(self.good[0], first)
        self.assertTrue(watch.wait_done([first.secs], 0), "no answer to a first view")
        memory = {"at start": resident_kib(self.pid)}
        clouds = rospy.get_param("~clouds", 300)  # fewer by hand, for a quick look
        checkpoint = min(100, clouds // 3)
        sent, waits = [], 0  # (cloud, stamp's seconds, time sent)
        start = next_at = time.monotonic()
        for i, cloud in enumerate(stream(self.good, self.kinds, clouds, checkpoint)):
            secs = [s for _, s, _ in sent]
            if watch.pending(secs) > AHEAD:  # hold back rather than let the node's queue drop
                waits += 1
                self.assertTrue(watch.wait_done(secs, AHEAD), "the node stopped answering")
                next_at = max(next_at, time.monotonic())
            time.sleep(max(0.0, next_at - time.monotonic()))
            next_at += PERIOD
            stamp = stamps()
            sent.append((cloud, stamp.secs, time.monotonic()))
            self.send(cloud, stamp)
            if i + 1 == checkpoint:
                self.assertTrue(watch.wait_done(secs + [stamp.secs], 0))
                time.sleep(0.5)
                memory["first"] = resident_kib(self.pid)
                next_at = time.monotonic()
        all_secs = [s for _, s, _ in sent]
        self.assertTrue(watch.wait_done(all_secs, 0), "clouds neither answered nor logged")
        seconds = time.monotonic() - start
        time.sleep(1.0)  # room for anything the node might still publish for a bad cloud
        memory["last"] = resident_kib(self.pid)
        self.check(sent, memory, waits, seconds, checkpoint)

    def check(self, sent, memory, waits, seconds, checkpoint):
        watch = self.watch
        latency, work, wrong, problems, rejected = [], [], [], [], {}
        for cloud, secs, at in sent:
            answers, logs = watch.answers.get(secs, []), watch.logs.get(secs, [])
            if cloud.labels is not None:
                if len(answers) != 1 or logs:
                    problems.append("%s at %d: %d answers, logs %s" % (cloud.kind, secs,
                                                                       len(answers), logs))
                    continue
                latency.append(answers[0][0] - at)
                if secs in watch.seconds:
                    work.append(watch.seconds[secs])
                if answers[0][1] != cloud.labels:
                    wrong.append("%s at %d" % (cloud.kind, secs))
                continue
            if answers:
                problems.append("%s at %d: answered" % (cloud.kind, secs))
            elif len(logs) != 1 or logs[0][0] != Log.ERROR or cloud.reason not in logs[0][1]:
                problems.append("%s at %d: logged %s, not one error holding '%s'" % (
                    cloud.kind, secs, logs, cloud.reason))
            else:
                rejected[cloud.kind] = rejected.get(cloud.kind, 0) + 1
        views = [c for c, _, _ in sent if c.labels is not None]
        growth = memory["last"] - memory["first"]
        report("\nstream: %d clouds in %.1f s, one every %.2f s asked (the publisher waited %d "
               "times for the node)" % (len(sent), seconds, PERIOD, waits))
        report("  views: %d sent, %d answered, %d with labels other than the tool's" % (
            len(views), len(latency), len(wrong)))
        report("  bad: %d sent, %d rejected with one error line each, by reason: %s" % (
            len(sent) - len(views), sum(rejected.values()),
            ", ".join("%s %d" % kv for kv in rejected.items())))
        report("  latency, cloud sent to labels received: %s; the segmentation's own (~stats): %s"
               % (spread(latency), spread(work)))
        report("  node memory (VmRSS): %.1f MiB after its first view, %.1f after %d clouds, %.1f "
               "after %d (%+.2f MiB since the %dth)" % (
                   memory["at start"] / 1024.0, memory["first"] / 1024.0, checkpoint,
                   memory["last"] / 1024.0, len(sent), growth / 1024.0, checkpoint))
        self.assertEqual(problems, [])
        self.assertEqual(watch.other_errors, [])
        self.assertEqual(wrong, [], "views labelled otherwise than by the tool")
        last, secs = next((c, s) for c, s, _ in reversed(sent) if c.labels is not None)
        self.assertEqual(watch.answers.get(secs, [(0, None)])[0][1], last.labels)
        self.assertTrue(os.path.exists("/proc/%d" % self.pid), "the node is gone")
        self.assertLess(growth, MEMORY_SLACK_KIB)


if __name__ == "__main__":
    rostest.rosrun("pcl_ncut_seg", "stream_test", StreamTest)
