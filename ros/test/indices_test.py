#!/usr/bin/python3
"""pcl_ncut_seg rostest: ~indices (exact and approximate sync), segments published as indices,
and lazy subscription, each on a node of indices.test."""
import os
import sys
import time
import unittest

import rosgraph.masterapi
import rospy
import rostest
from pcl_msgs.msg import PointIndices
from std_msgs.msg import Header

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ros_test_support import (Collector, PointCloud2, Stamps, dumbbell, labels,  # noqa: E402
                              make_cloud, wait_for_connection)


def subscribers(topic):
    _, subs, _ = rosgraph.masterapi.Master("/indices_test").getSystemState()
    return next((nodes for name, nodes in subs if name == topic), [])


class IndicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("indices_test")
        cls.stamps = Stamps()
        cls.points = dumbbell(1500, 3)
        cls.left = [i for i, p in enumerate(cls.points) if p[0] < 0.4]

    def inputs(self, node, with_indices):
        output = Collector(node + "/output",
                           PointIndices if node == "/seg_publish" else PointCloud2)
        cloud = rospy.Publisher(node + "/input", PointCloud2, queue_size=10)
        self.assertTrue(wait_for_connection(cloud))
        indices = None
        if with_indices:
            indices = rospy.Publisher(node + "/indices", PointIndices, queue_size=10)
            self.assertTrue(wait_for_connection(indices))
        return output, cloud, indices

    def check_left_only(self, out):
        self.assertIsNotNone(out, "no output")
        got = labels(out)
        left = set(self.left)
        for i, (_, label) in enumerate(got):
            self.assertEqual(label != 0, i in left, i)
        self.assertEqual({label for _, label in got} - {0}, {1, 2})

    def test_indices_exactly_synchronized(self):
        output, cloud_pub, indices_pub = self.inputs("/seg_indices", True)
        stamp = self.stamps()
        indices_pub.publish(PointIndices(header=Header(stamp=stamp, frame_id="sensor"),
                                         indices=self.left))
        cloud_pub.publish(make_cloud(self.points, stamp))
        self.check_left_only(output.wait(lambda m: m.header.stamp == stamp))

    def test_indices_approximately_synchronized(self):
        output, cloud_pub, indices_pub = self.inputs("/seg_approx", True)
        first = self.stamps()
        # Two pairs 10 ms apart: the second lets the policy settle the first.
        for stamp in (first, self.stamps()):
            indices_pub.publish(PointIndices(header=Header(stamp=stamp + rospy.Duration(0.01),
                                                           frame_id="sensor"),
                                             indices=self.left))
            cloud_pub.publish(make_cloud(self.points, stamp))
            time.sleep(0.2)
        self.check_left_only(output.wait(lambda m: m.header.stamp == first))

    def test_segments_published_as_indices(self):
        output, cloud_pub, _ = self.inputs("/seg_publish", False)
        stamp = self.stamps()
        cloud_pub.publish(make_cloud(self.points, stamp))
        self.assertIsNotNone(output.wait(lambda m: m.header.stamp == stamp
                                         and output.count(lambda n: n.header.stamp == stamp) == 3))
        time.sleep(0.5)
        segments = [m for m in output.messages if m.header.stamp == stamp]
        self.assertEqual(len(segments), 3)  # ~segments: 3
        seen = [i for m in segments for i in m.indices]
        self.assertEqual(sorted(seen), list(range(len(self.points))))  # each point once
        for m in segments:
            self.assertEqual(m.header.frame_id, "sensor")
            self.assertEqual(list(m.indices), sorted(m.indices))
        # Segments come ordered by their smallest index.
        firsts = [m.indices[0] for m in segments]
        self.assertEqual(firsts, sorted(firsts))

    def test_input_is_subscribed_only_while_output_is(self):
        self.assertNotIn("/seg_lazy", subscribers("/seg_lazy/input"))
        sub = rospy.Subscriber("/seg_lazy/output", PointCloud2, lambda m: None)
        deadline = time.time() + 30
        while "/seg_lazy" not in subscribers("/seg_lazy/input") and time.time() < deadline:
            time.sleep(0.1)
        self.assertIn("/seg_lazy", subscribers("/seg_lazy/input"))
        sub.unregister()
        deadline = time.time() + 30
        while "/seg_lazy" in subscribers("/seg_lazy/input") and time.time() < deadline:
            time.sleep(0.1)
        self.assertNotIn("/seg_lazy", subscribers("/seg_lazy/input"))


if __name__ == "__main__":
    rostest.rosrun("pcl_ncut_seg", "indices_test", IndicesTest)
