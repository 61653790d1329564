#!/usr/bin/python3
"""rostest (twin_picks.test, docs/twin.md "Picks and set-downs"): a twin told 3 t follows a real
crane lifting 4 t off the ground and setting it down.

Checked, by the wall time at which this test receives each crane/state (a twin that falls
behind real time stamps its states with its own simulated time, earlier than the wall's):
- the real crane's load leaves the ground (its crane/state payload_landed goes 0);
- 10 s later the twin's crane/state payload_mass_estimate is within 3 % of 4000 kg, and a
  forecast made after the twin took the estimate arrives (the forecaster runs with it);
- the real crane sets the load down; the twin's payload_landed, 0 since its own lift-off, is 1
  again within 1 s of it;
- the twin's crane/usage counts one lift, of the mass its load cell found (within 3 % of 4 t),
  with a dynamic factor above 1 (printed with the real crane's).
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Path

from crane_twin.msg import CraneState, CraneUsage

REAL_MASS = 4000.0


class Recorder:
    def __init__(self):
        self.lock = threading.Lock()
        self.real = []      # (received, landed)
        self.twin = []      # (received, landed, mass estimate)
        self.rtf = []       # (received, twin's real-time factor)
        self.forecasts = []  # received
        rospy.Subscriber("/real/crane/state", CraneState, self.on_real, queue_size=500)
        rospy.Subscriber("/crane/state", CraneState, self.on_twin, queue_size=500)
        rospy.Subscriber("/crane/forecast", Path, self.on_forecast, queue_size=20)
        self.usage = None
        self.real_usage = None
        rospy.Subscriber("/crane/usage", CraneUsage, self.on_usage, queue_size=5)
        rospy.Subscriber("/real/crane/usage", CraneUsage, self.on_real_usage, queue_size=5)
        self.diag = {}  # the twin's latest simulation diagnostics
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diag, queue_size=50)

    def on_diag(self, m):
        for s in m.status:
            if s.name.endswith("/crane_sim_node: simulation") and not s.name.startswith("/real"):
                with self.lock:
                    self.diag = {kv.key: kv.value for kv in s.values}

    def on_usage(self, m):
        with self.lock:
            self.usage = m

    def on_real_usage(self, m):
        with self.lock:
            self.real_usage = m

    def on_real(self, m):
        with self.lock:
            self.real.append((time.time(), m.payload_landed))

    def on_twin(self, m):
        with self.lock:
            self.twin.append((time.time(), m.payload_landed, m.payload_mass_estimate))
            self.rtf.append((time.time(), m.real_time_factor))

    def on_forecast(self, m):
        with self.lock:
            self.forecasts.append(time.time())


def say(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


def first(rows, predicate, after):
    for r in rows:
        if r[0] > after and predicate(r):
            return r
    return None


class TwinFollowsPicks(unittest.TestCase):
    def test_picks(self):
        rec = Recorder()
        deadline = time.time() + 150.0
        lift = set_down = None
        while time.time() < deadline:
            with rec.lock:
                real = list(rec.real)
            if real and lift is None:
                r = first(real, lambda r: not r[1], real[0][0])
                lift = r[0] if r else None
            if lift is not None and set_down is None:
                r = first(real, lambda r: r[1], lift)
                set_down = r[0] if r else None
            if set_down is not None and real[-1][0] > set_down + 3.0:
                break
            time.sleep(0.2)
        self.assertIsNotNone(lift, "the real crane's load never left the ground")
        self.assertIsNotNone(set_down, "the real crane never set its load down")
        with rec.lock:
            twin = list(rec.twin)
            forecasts = list(rec.forecasts)
        self.assertTrue(twin, "no crane/state from the twin")
        with rec.lock:
            rtf = sorted(r for t, r in rec.rtf if t > lift)
        if rtf:
            say("twin's real-time factor after the lift-off: min %.2f, median %.2f" %
                (rtf[0], rtf[len(rtf) // 2]))
        say("real crane: first state %.2f s, lift-off %.2f s, set-down %.2f s; twin states "
            "%.2f to %.2f s (received)" % (real[0][0], lift, set_down, twin[0][0], twin[-1][0]))
        at10 = first(twin, lambda r: True, lift + 10.0)
        self.assertIsNotNone(at10, "no twin state 10 s after the lift-off")
        told = twin[0][2]
        took = first(twin, lambda r: abs(r[2] - told) > 1.0, lift)
        say("the twin took its estimate %s s after the real lift-off (received)" %
            ("%.2f" % (took[0] - lift) if took else "never"))
        say("real lift-off at %.2f s, set-down at %.2f s; twin told %.0f kg, "
            "estimate 10 s after the lift-off %.1f kg (received)" % (lift, set_down, told, at10[2]))
        self.assertAlmostEqual(told, 3000.0, delta=1.0)
        self.assertLess(abs(at10[2] - REAL_MASS), 0.03 * REAL_MASS)
        taken = took
        self.assertIsNotNone(taken)
        self.assertTrue(any(t > taken[0] for t in forecasts),
                        "no forecast after the twin took %.0f kg" % taken[2])
        # The twin's own lift-off (its told 3 t leaves the ground before the real 4 t; a twin
        # that fell behind real time lifts later), then its load landed again: the set-down.
        twin_lift = first(twin, lambda r: not r[1], twin[0][0])
        self.assertIsNotNone(twin_lift, "the twin's load never left the ground")
        seen = first(twin, lambda r: r[1], max(twin_lift[0], lift) + 1.0)
        self.assertIsNotNone(seen, "the twin never saw the set-down")
        say("twin sees the set-down at %.2f s: %.2f s after the real crane" %
            (seen[0], seen[0] - set_down))
        self.assertLess(seen[0] - set_down, 1.0)
        self.assertGreater(seen[0] - set_down, -0.2)
        with rec.lock:
            usage = rec.usage
        self.assertIsNotNone(usage, "no crane/usage from the twin")
        say("twin's usage: %d lift(s) of %s kg, phi_2 %s" %
            (usage.lifts, list(usage.lift_masses), list(usage.lift_factors)))
        self.assertEqual(usage.lifts, 1)
        self.assertLess(abs(usage.lift_masses[0] - REAL_MASS), 0.03 * REAL_MASS)
        # The twin lifts its told 3 t at the crane's hoist speed in its own time: this scene
        # lifts 3 t with phi_2 = 1.24 (`crane_sim run config/scenes/t8036_lift_off_slow.yaml
        # --set payload.mass=3000`; 4 t: 1.18). Printed, not asserted, with the twin's pacing
        # overruns and refused joint samples: nine runs read 1.24 to 1.29 and one 1.72, not yet
        # understood (docs/twin.md "Picks and set-downs").
        with rec.lock:
            real_usage = rec.real_usage
        self.assertIsNotNone(real_usage, "no crane/usage from the real crane")
        self.assertEqual(real_usage.lifts, 1)
        say("real crane's usage: phi_2 %s" % list(real_usage.lift_factors))
        with rec.lock:
            diag = dict(rec.diag)
        say("twin's pacing overruns %s, joint samples refused %s" %
            (diag.get("pacing_overruns", "?"), diag.get("joint_samples_refused", "?")))
        self.assertGreater(usage.lift_factors[0], 1.0)


if __name__ == "__main__":
    rospy.init_node("twin_follows_picks")
    rostest.rosrun("crane_twin", "twin_follows_picks", TwinFollowsPicks, sys.argv)
