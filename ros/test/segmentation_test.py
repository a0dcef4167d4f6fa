#!/usr/bin/python3
"""pcl_ncut_seg rostest: a segmentation (node or nodelet) under a real master.

Private parameters: ~node, the segmentation's namespace (/seg); ~log_name, the process whose
/rosout errors it reports (the node, or the nodelet manager); ~startup, also start a node with
bad start-up parameters.
"""
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import dynamic_reconfigure.client
import roslib.packages
import rospy
import rostest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ros_test_support import (Collector, Log, PointCloud2, Stamps, String,  # noqa: E402
                              dumbbell, labels, make_cloud, stats, wait_for_connection)

NAN = float("nan")


class SegmentationTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("segmentation_test")
        cls.node = rospy.get_param("~node", "/seg")
        cls.log_name = rospy.get_param("~log_name", cls.node)
        cls.stamps = Stamps()
        cls.logs = Collector("/rosout", Log)
        cls.stats = Collector(cls.node + "/stats", String)
        cls.output = Collector(cls.node + "/output", PointCloud2)  # the input follows (lazy)
        cls.pub = rospy.Publisher(cls.node + "/input", PointCloud2, queue_size=10)
        assert wait_for_connection(cls.pub), "the segmentation did not subscribe to ~input"
        cls.reconfigure = dynamic_reconfigure.client.Client(cls.node, timeout=30)
        cls.points = dumbbell(1500, 3)

    def configure(self, **values):
        return self.reconfigure.update_configuration(values)

    def segment(self, cloud):
        """Publish the cloud; its output (by stamp), or None."""
        self.pub.publish(cloud)
        return self.output.wait(lambda m: m.header.stamp == cloud.header.stamp)

    def error_after(self, action, text, tries=15):
        """Do the action until a ROS error containing text comes on /rosout (the first ones
        can come before /rosout's connection to the node), or give up: the error, or None."""
        for _ in range(tries):
            action()
            error = self.logs.wait(lambda m: m.level == Log.ERROR and m.name == self.log_name
                                   and text in m.msg, 1.0)
            if error:
                return error
        return None

    def test_01_startup_parameters_reach_dynamic_reconfigure(self):
        config = self.reconfigure.get_configuration(timeout=10)
        self.assertEqual(config["segments"], 2)
        self.assertEqual(config["stopping"], "count")  # ~segments chose the count rule
        self.assertEqual(config["boundary_band"], 0.0)  # ~boundary_band: off

    def test_labels_in_order_with_the_header(self):
        self.configure(segments=2)
        cloud = make_cloud(self.points, self.stamps())
        out = self.segment(cloud)
        self.assertIsNotNone(out, "no output")
        self.assertEqual(out.header.frame_id, "sensor")
        self.assertEqual(out.header.stamp, cloud.header.stamp)
        self.assertEqual((out.width, out.height), (cloud.width, cloud.height))
        got = labels(out)
        self.assertEqual(len(got), len(self.points))
        for (x, _), p in zip(got, self.points):
            self.assertAlmostEqual(x, p[0], places=5)  # each point in its place
        self.assertEqual({label for _, label in got}, {1, 2})
        left = {label for x, label in got if x < -1.3}
        right = {label for x, label in got if x > 1.3}
        self.assertEqual(len(left), 1)
        self.assertEqual(len(right), 1)
        self.assertNotEqual(left, right)

    def test_organized_cloud_stays_organized(self):
        self.configure(segments=2)
        points = [(NAN, NAN, NAN) if i % 7 == 0 else p for i, p in enumerate(self.points)]
        cloud = make_cloud(points, self.stamps(), width=50, height=30)
        out = self.segment(cloud)
        self.assertIsNotNone(out, "no output")
        self.assertEqual((out.width, out.height), (50, 30))
        self.assertFalse(out.is_dense)
        got = labels(out)
        for i, (x, label) in enumerate(got):
            self.assertEqual(label == 0, i % 7 == 0, i)
            self.assertEqual(math.isnan(x), i % 7 == 0, i)

    def test_bad_clouds_get_an_error_and_the_node_keeps_serving(self):
        from sensor_msgs.msg import PointField
        no_xyz = [PointField("a", 0, PointField.FLOAT32, 1)]
        bad = [
            (make_cloud([(1.0,)] * 10, self.stamps(), fields=no_xyz), "no field x"),
            (make_cloud([], self.stamps()), "empty"),
            (make_cloud([(NAN, NAN, NAN)] * 20, self.stamps()), "no finite point"),
        ]
        for cloud, why in bad:
            self.assertIsNotNone(self.error_after(lambda: self.pub.publish(cloud), why),
                                 "no ROS error naming '%s'" % why)
        time.sleep(0.5)
        for cloud, _ in bad:
            self.assertEqual(self.output.count(lambda m: m.header.stamp == cloud.header.stamp), 0)
        self.assertIsNotNone(self.segment(make_cloud(self.points, self.stamps())))

    def test_reconfigure_recuts_the_last_cloud_without_analysis(self):
        self.configure(segments=2)
        cloud = make_cloud(self.points, self.stamps())
        self.assertIsNotNone(self.segment(cloud))
        stamp = cloud.header.stamp.to_sec()
        first = self.stats.wait(lambda m: stats(m)["stamp"] == stamp)
        self.assertIsNotNone(first)
        before = stats(first)
        self.assertTrue(before["analysed"])
        config = self.configure(segments=3)
        self.assertEqual(config["segments"], 3)
        self.assertEqual(config["stopping"], "count")
        again = self.output.wait(lambda m: m.header.stamp == cloud.header.stamp
                                 and {label for _, label in labels(m)} == {1, 2, 3})
        self.assertIsNotNone(again, "the last cloud was not re-cut into 3 segments")
        self.assertEqual(again.header.frame_id, "sensor")
        recut = self.stats.wait(lambda m: stats(m)["stamp"] == stamp
                                and stats(m)["cuts"] == before["cuts"] + 1)
        self.assertIsNotNone(recut)
        self.assertFalse(stats(recut)["analysed"])
        self.assertEqual(stats(recut)["analyses"], before["analyses"])
        self.assertEqual(stats(recut)["segments"], 3)

    def test_reconfigure_rejects_a_value_out_of_range(self):
        configs = []
        error = self.error_after(lambda: configs.append(self.configure(beta=0.0)),
                                 "beta must be a number > 0")
        self.assertIsNotNone(error)
        self.assertEqual(configs[-1]["beta"], 2.0)  # kept

    def test_startup_parameters_out_of_range_are_reported(self):
        if not rospy.get_param("~startup", False):
            self.skipTest("only with ~startup")
        exe = roslib.packages.find_node("pcl_ncut_seg", "pcl_ncut_seg_node")[0]
        with tempfile.TemporaryFile("w+") as log:
            # A file, not a pipe: nothing blocks on the node's buffered output.
            proc = subprocess.Popen(
                [exe, "__name:=seg_startup", "_k:=1", "_threshold:=-1", "_boundary_band:=off",
                 "_bogus:=3"], stdout=log, stderr=log)
            try:
                client = dynamic_reconfigure.client.Client("/seg_startup", timeout=30)
                config = client.get_configuration(timeout=10)
                self.assertEqual(config["threshold"], 0.1)  # the default, kept
                self.assertEqual(config["boundary_band"], 0.0)  # off
                log.seek(0)
                text = log.read()
                self.assertIn("k must be an integer >= 2, got '1'; keeping 10", text)
                self.assertIn("threshold must be a number >= 0, got '-1'; keeping 0.1", text)
                self.assertIn("~bogus is no parameter", text)
            finally:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()

if __name__ == "__main__":
    rostest.rosrun("pcl_ncut_seg", "segmentation_test", SegmentationTest)
