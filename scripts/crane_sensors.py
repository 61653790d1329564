#!/usr/bin/python3
"""Simulated sensors on a crane (docs/twin.md): read a crane_sim_node standing in for a real
crane (its joint_states and crane/state under ~source_ns) and publish what a real crane's
sensors would give a twin, with noise:

  crane/measured_joint_states  sensor_msgs/JointState  slew, trolley, hoist positions (+ noise
                               ~joint_noise [rad, m, m]; velocities only if ~joint_velocities),
                               at the source's rate
  crane/measured_payload       geometry_msgs/PointStamped in `world` at ~payload_rate Hz,
                               Gaussian noise ~payload_noise [m] per axis (camera, GNSS)
  crane/measured_tension       std_msgs/Float64 [N] at ~tension_rate Hz, relative noise
                               ~tension_noise (load cell)

~enable_payload (std_srvs/SetBool) switches the payload measurements off and on. The source
crane's base must be at the world origin (no site pose). Seeded (~seed) so runs repeat.
"""
import random
import threading

import rospy
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from std_srvs.srv import SetBool, SetBoolResponse

from crane_twin.msg import CraneState


class Sensors:
    def __init__(self):
        ns = rospy.get_param("~source_ns", "/real").rstrip("/")
        self.payload_noise = float(rospy.get_param("~payload_noise", 0.05))
        self.joint_noise = [float(x) for x in rospy.get_param("~joint_noise", [1e-4, 0.005, 0.005])]
        self.velocities = bool(rospy.get_param("~joint_velocities", False))
        self.tension_noise = float(rospy.get_param("~tension_noise", 0.01))
        payload_rate = float(rospy.get_param("~payload_rate", 5.0))
        tension_rate = float(rospy.get_param("~tension_rate", 10.0))
        for name, v in (("payload_noise", self.payload_noise), ("tension_noise", self.tension_noise)):
            if not v >= 0.0:
                raise ValueError("~%s must be >= 0, got %r" % (name, v))
        if len(self.joint_noise) != 3 or min(self.joint_noise) < 0.0:
            raise ValueError("~joint_noise must be 3 numbers >= 0 [rad, m, m]")
        if not (payload_rate > 0.0 and tension_rate > 0.0):
            raise ValueError("~payload_rate and ~tension_rate must be > 0")
        self.rng = random.Random(int(rospy.get_param("~seed", 1)))
        self.lock = threading.Lock()
        self.state = None
        self.payload_on = True
        self.joint_pub = rospy.Publisher("crane/measured_joint_states", JointState, queue_size=50)
        self.payload_pub = rospy.Publisher("crane/measured_payload", PointStamped, queue_size=10)
        self.tension_pub = rospy.Publisher("crane/measured_tension", Float64, queue_size=10)
        rospy.Subscriber(ns + "/joint_states", JointState, self.on_joints, queue_size=50)
        rospy.Subscriber(ns + "/crane/state", CraneState, self.on_state, queue_size=50)
        rospy.Service("~enable_payload", SetBool, self.on_enable)
        rospy.Timer(rospy.Duration(1.0 / payload_rate), self.publish_payload)
        rospy.Timer(rospy.Duration(1.0 / tension_rate), self.publish_tension)

    def on_enable(self, req):
        self.payload_on = req.data
        return SetBoolResponse(True, "payload measurements " + ("on" if req.data else "off"))

    def on_joints(self, m):
        out = JointState()
        out.header.stamp = m.header.stamp
        with self.lock:
            for name, pos, vel in zip(m.name, m.position, m.velocity or [0.0] * len(m.name)):
                if name not in ("slew", "trolley", "hoist"):
                    continue
                sigma = self.joint_noise[("slew", "trolley", "hoist").index(name)]
                out.name.append(name)
                out.position.append(pos + self.rng.gauss(0.0, sigma))
                if self.velocities:
                    out.velocity.append(vel)
        self.joint_pub.publish(out)

    def on_state(self, m):
        with self.lock:
            self.state = m

    def publish_payload(self, _):
        with self.lock:
            s = self.state
            if s is None or not self.payload_on:
                return
            p = PointStamped()
            p.header.stamp = s.header.stamp
            p.header.frame_id = "world"
            p.point.x = s.payload.x + self.rng.gauss(0.0, self.payload_noise)
            p.point.y = s.payload.y + self.rng.gauss(0.0, self.payload_noise)
            p.point.z = s.payload.z + self.rng.gauss(0.0, self.payload_noise)
        self.payload_pub.publish(p)

    def publish_tension(self, _):
        with self.lock:
            s = self.state
            if s is None:
                return
            t = s.rope_top_tension * (1.0 + self.rng.gauss(0.0, self.tension_noise))
        self.tension_pub.publish(Float64(t))


def main():
    rospy.init_node("crane_sensors")
    try:
        Sensors()
    except ValueError as e:
        rospy.logfatal("crane_sensors: %s", e)
        raise SystemExit(2)
    rospy.spin()


if __name__ == "__main__":
    main()
