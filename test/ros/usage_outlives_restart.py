#!/usr/bin/python3
"""rostest (usage_lifetime.test, docs/fatigue.md "Lifetime counts"): crane_sim_node's usage count
outlives the node, and its usage diagnostics WARN against the crane file's design hours.

The test starts crane_sim_node itself on the live T8036 scene (20 rope elements), with
~usage_file in a temporary folder and a copy of the T8036 crane file whose design_hours it sets:
- run 1 (design_hours 1e12): crane/usage names the file and its hours and damage grow; the
  status "<node>: usage" is WARN and names every hot spot (a damage rate > 0 reaches D = 1
  before 1e12 h); after SIGINT the node exits 0 and the file holds at least the last count
  published (its hours);
- run 2 (design_hours 1, the same hot spots): crane/usage goes on from the file (hours not
  below the file's, damage not below run 1's last); the status is OK;
- a usage file of other hot spots: the node exits with status 2 naming the file.
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import roslib.packages
import rospkg
import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

from crane_twin.msg import CraneUsage

NODE = "usage_node"
HOT_SPOTS = ["mast_foot", "mast_top", "jib_root", "counter_jib_root"]


def say(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


class Listener:
    def __init__(self):
        self.lock = threading.Lock()
        self.usage = None
        self.status = None
        rospy.Subscriber("/crane/usage", CraneUsage, self.on_usage, queue_size=5)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diag, queue_size=20)

    def on_usage(self, m):
        with self.lock:
            self.usage = m

    def on_diag(self, m):
        with self.lock:
            for s in m.status:
                if s.name == "/%s: usage" % NODE:
                    self.status = s

    def clear(self):
        with self.lock:
            self.usage = self.status = None

    def wait(self, ok, timeout, process):
        end = time.time() + timeout
        while time.time() < end and not rospy.is_shutdown() and process.poll() is None:
            with self.lock:
                if ok(self.usage, self.status):
                    return self.usage, self.status
            time.sleep(0.1)
        with self.lock:
            return self.usage, self.status


class UsageOutlivesRestart(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="usage_lifetime_")
        self.root = rospkg.RosPack().get_path("crane_twin")
        self.node = roslib.packages.find_node("crane_twin", "crane_sim_node")[0]
        self.usage_file = os.path.join(self.dir, "usage.yaml")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def crane_file(self, design_hours):
        with open(os.path.join(self.root, "config/cranes/t8036.yaml")) as f:
            text = f.read()
        text, n = re.subn(r"(?m)^design_hours:.*$", "design_hours: %r" % design_hours, text)
        self.assertEqual(n, 1, "the T8036 file has no design_hours line")
        path = os.path.join(self.dir, "crane_%g.yaml" % design_hours)
        with open(path, "w") as f:
            f.write(text)
        return path

    def start(self, design_hours):
        ns = "/%s/" % NODE
        rospy.set_param(ns + "scene", os.path.join(self.root, "config/scenes/t8036_live.yaml"))
        rospy.set_param(ns + "overrides", ["rope.elements=20", "duration=600",
                                           "crane=" + self.crane_file(design_hours)])
        rospy.set_param(ns + "usage_file", self.usage_file)
        rospy.set_param(ns + "usage_save_period", 1.0)
        rospy.set_param(ns + "command_timeout", 0.0)
        return subprocess.Popen([self.node, "__name:=" + NODE], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)

    def stop(self, p):
        p.send_signal(signal.SIGINT)
        try:
            out, _ = p.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            p.kill()
            out, _ = p.communicate()
            self.fail("the node did not stop on SIGINT: " + out[-2000:])
        self.assertEqual(p.returncode, 0, out[-2000:])

    def test_usage_outlives_restart(self):
        listen = Listener()
        # Run 1: a design life no hot spot reaches.
        p = self.start(1e12)
        try:
            usage, status = listen.wait(
                lambda u, s: u is not None and s is not None and u.hours > 4.0 / 3600.0
                and len(u.damage) == 4 and min(u.damage) > 0.0 and s.level == DiagnosticStatus.WARN,
                60.0, p)
            self.assertIsNotNone(usage, "no crane/usage from the node")
            self.assertIsNotNone(status, "no usage status in /diagnostics")
            say("run 1: %.5f h, damage %s; %s" % (usage.hours, list(usage.damage), status.message))
            self.assertEqual(usage.usage_file, self.usage_file)
            self.assertEqual(list(usage.hot_spots), HOT_SPOTS)
            self.assertEqual(usage.design_hours, 1e12)
            self.assertTrue(all(usage.short_of_design_life))
            self.assertEqual(status.level, DiagnosticStatus.WARN, status.message)
            for name in HOT_SPOTS:
                self.assertIn(name, status.message)
            last = usage
        finally:
            self.stop(p)
        with open(self.usage_file) as f:
            saved = yaml.safe_load(f)
        say("file after run 1: %.5f h, %d turning points of mast_foot pending" %
            (saved["hours"], len(saved["hot_spots"][0]["turning_points"])))
        self.assertGreaterEqual(saved["hours"], last.hours)
        self.assertEqual([h["name"] for h in saved["hot_spots"]], HOT_SPOTS)
        # Run 2: the count goes on from the file; a design life of 1 h every hot spot outlives.
        listen.clear()
        p = self.start(1.0)
        try:
            usage, status = listen.wait(
                lambda u, s: u is not None and s is not None and u.design_hours == 1.0, 60.0, p)
            self.assertIsNotNone(usage, "no crane/usage from the restarted node")
            self.assertIsNotNone(status, "no usage status from the restarted node")
            say("run 2: %.5f h, damage %s; %s" % (usage.hours, list(usage.damage), status.message))
            self.assertGreaterEqual(usage.hours, saved["hours"])
            # A history that goes on never lowers its Miner sum (closed cycles and residue).
            for d, before in zip(usage.damage, last.damage):
                self.assertGreaterEqual(d, before * (1.0 - 1e-12))
            self.assertEqual(status.level, DiagnosticStatus.OK, status.message)
            self.assertFalse(any(usage.short_of_design_life))
        finally:
            self.stop(p)
        # A count of other hot spots is refused, the file named.
        with open(self.usage_file, "w") as f:
            f.write("hours: 1.0\nlifts: 0\nmax_load: 12500\nmass_ratio_cubed_sum: 0\n"
                    "hot_spots:\n  - {name: boom_tip, detail_category: 71, closed_cycles_damage: 0.1, "
                    "turning_points: [], pending: []}\n")
        p = self.start(1.0)
        try:
            out, _ = p.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            p.kill()
            self.fail("a node given another crane's usage file kept running")
        say("refused: " + out.strip().splitlines()[-1] if out.strip() else "no output")
        self.assertEqual(p.returncode, 2, out[-2000:])
        self.assertIn(self.usage_file, out)
        self.assertIn("boom_tip", out)


if __name__ == "__main__":
    rospy.init_node("usage_outlives_restart")
    rostest.rosrun("crane_twin", "usage_outlives_restart", UsageOutlivesRestart)
