"""pcl_ncut_seg rostests: generated clouds, a topic collector, label reading.

No numpy: plain Python, deterministic for a seed.
"""
import math
import random
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rosnode

import rospy
import yaml
from rosgraph_msgs.msg import Log
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header, String

FIELDS_XYZ = [
    PointField("x", 0, PointField.FLOAT32, 1),
    PointField("y", 4, PointField.FLOAT32, 1),
    PointField("z", 8, PointField.FLOAT32, 1),
]


def dumbbell(n=1500, seed=3):
    """Two balls of radius 0.5 at x = -1.2 and 1.2 joined by a bar of radius 0.12 (the
    outer surface, uniform by area): points as (x, y, z) tuples."""
    rng = random.Random(seed)
    ball, bar, centre = 0.5, 0.12, 1.2
    areas = [4 * math.pi * ball**2, 4 * math.pi * ball**2, 2 * math.pi * bar * 2 * centre]
    points = []
    while len(points) < n:
        which = rng.choices(range(3), weights=areas)[0]
        if which < 2:
            cx = -centre if which == 0 else centre
            z, phi = rng.uniform(-1, 1), rng.uniform(0, 2 * math.pi)
            s = math.sqrt(1 - z * z)
            p = (cx + ball * s * math.cos(phi), ball * s * math.sin(phi), ball * z)
            if abs(p[0]) <= centre and p[1] ** 2 + p[2] ** 2 < bar**2:
                continue  # inside the bar
        else:
            a = rng.uniform(0, 2 * math.pi)
            p = (rng.uniform(-centre, centre), bar * math.cos(a), bar * math.sin(a))
            if min(math.dist(p, (-centre, 0, 0)), math.dist(p, (centre, 0, 0))) < ball:
                continue  # inside a ball
        points.append(p)
    return points


def make_cloud(points, stamp, frame="sensor", width=None, height=1, fields=None):
    """A PointCloud2 of the points (x y z FLOAT32), organized width x height if given."""
    header = Header(stamp=stamp, frame_id=frame)
    msg = point_cloud2.create_cloud(header, fields or FIELDS_XYZ, points)
    if width is not None:
        msg.width, msg.height = width, height
        msg.row_step = msg.point_step * width
    msg.is_dense = all(all(math.isfinite(c) for c in p[:3]) for p in points)
    return msg


def labels(msg):
    """(x, label) of each point of a labelled cloud, in order."""
    names = [f.name for f in msg.fields]
    assert names == ["x", "y", "z", "rgb", "label"], names
    return [(p[0], p[1]) for p in point_cloud2.read_points(msg, ("x", "label"), skip_nans=False)]


class Collector:
    """Keeps every message of a topic; wait() for one that satisfies a predicate."""

    def __init__(self, topic, msg_type):
        self.messages = []
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, msg_type, self._add, queue_size=100)

    def _add(self, msg):
        with self.cond:
            self.messages.append(msg)
            self.cond.notify_all()

    def wait(self, predicate, timeout=30.0):
        deadline = time.time() + timeout
        with self.cond:
            while True:
                for m in self.messages:
                    if predicate(m):
                        return m
                left = deadline - time.time()
                if left <= 0 or rospy.is_shutdown():
                    return None
                self.cond.wait(min(left, 0.5))

    def count(self, predicate):
        with self.cond:
            return sum(1 for m in self.messages if predicate(m))


class Stamps:
    """A new stamp for each cloud, so that each test knows its output."""

    def __init__(self, start=1000):
        self.next = start

    def __call__(self):
        self.next += 1
        return rospy.Time(self.next, 250000000)


def wait_for_connection(pub, timeout=30.0):
    deadline = time.time() + timeout
    while pub.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.05)
    return pub.get_num_connections() > 0


def report(text):
    """Print figures where the test's output shows them: the terminal (rosunit keeps stdout for
    its XML file, where they go too)."""
    print(text)
    sys.__stderr__.write(text + "\n")
    sys.__stderr__.flush()


def stats(msg):
    return yaml.safe_load(msg.data)


def _node_api(node):
    return xmlrpc.client.ServerProxy(rosnode.get_api_uri(rosgraph.Master(rospy.get_name()), node))


def wait_for_log_connection(node, timeout=30.0):
    """Wait until the node's /rosout reaches this process (its messages before are lost)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        _, _, bus = _node_api(node).getBusInfo(rospy.get_name())
        if any(c[2] == "o" and c[4] == "/rosout" and c[1] == rospy.get_name() for c in bus):
            return True
        time.sleep(0.1)
    return False


def node_pid(node):
    return _node_api(node).getPid(rospy.get_name())[2]


def resident_kib(pid):
    """The process' resident memory (VmRSS), in KiB."""
    with open("/proc/%d/status" % pid) as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))


__all__ = ["Collector", "Log", "PointCloud2", "Stamps", "String", "dumbbell", "labels",
           "make_cloud", "node_pid", "report", "resident_kib", "stats", "wait_for_connection",
           "wait_for_log_connection"]
