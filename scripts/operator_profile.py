#!/usr/bin/python3
"""A scripted crane operator for crane_sim_node (docs/ros.md): unpauses the simulator if it
waits, then sends crane/command at 10 Hz following a profile in *simulated* time (read from
crane/state), and finally falls silent so the node's command timeout brings the drives to rest.

Profile (default): 0-2 s rest; 2-8 s trolley in at 0.8 m/s; 8-15 s slew at 0.06 rad/s;
15 s on: silence.  Usage: operator_profile.py [--end 15]
"""
import argparse
import sys
import time

import rospy
from std_srvs.srv import SetBool

from crane_twin.msg import CraneCommand, CraneState


def command_at(t):
    """(slew_rate, trolley_speed, hoist_speed) of the profile at simulated time t."""
    if t < 2.0:
        return 0.0, 0.0, 0.0
    if t < 8.0:
        return 0.0, -0.8, 0.0
    return 0.06, 0.0, 0.0


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--end", type=float, default=15.0, help="simulated time to fall silent")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("operator_profile")
    sim_t = [None]
    rospy.Subscriber("crane/state", CraneState, lambda m: sim_t.__setitem__(0, m.t))
    pub = rospy.Publisher("crane/command", CraneCommand, queue_size=10)
    rospy.wait_for_service("crane_sim_node/pause", timeout=120)
    # Wall-clock waits throughout: with use_sim_time set, rospy.sleep and rospy.Rate wait for a
    # /clock that a paused simulator does not advance.
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.05)
    rospy.ServiceProxy("crane_sim_node/pause", SetBool)(False)
    # The profile itself follows simulated time from crane/state.
    last_t, last_change = None, time.time()
    while not rospy.is_shutdown():
        t = sim_t[0]
        if t is not None and t >= args.end:
            break
        if t != last_t:
            last_t, last_change = t, time.time()
        elif time.time() - last_change > 30.0:
            rospy.logerr("operator_profile: no simulated time progress for 30 s; giving up")
            return 1
        if t is not None:
            c = CraneCommand()
            c.header.stamp = rospy.Time.now()
            c.slew_rate, c.trolley_speed, c.hoist_speed = command_at(t)
            pub.publish(c)
        time.sleep(0.1)
    rospy.loginfo("operator_profile: silent from t = %.2f s", sim_t[0] or 0.0)
    return 0


if __name__ == "__main__":
    sys.exit(main())
