#!/usr/bin/python3
"""Turn a crane_sim_node recording into crane_sim's formats.

  bag_to_series.py BAG [--series OUT.csv] [--commands OUT.yaml] [--stats]

--series    crane/state as a docs/cli.md time-series CSV (crane_sim compare and plot_series.py
            read it; full_order_steps from the node's latest /diagnostics, 1 Hz);
--commands  crane/command_applied as a scene `commands:` schedule (YAML flow list, simulated
            times), so `crane_sim run SCENE --set "commands=$(cat OUT.yaml)"` repeats the run;
--stats     median step cost, real-time factor and the count of states and commands.
"""
import argparse
import statistics
import sys

import rosbag

COLUMNS = ("t,payload_x,payload_y,payload_z,payload_vx,payload_vy,payload_vz,cab_dx,cab_dy,"
           "cab_dz,jib_tip_dx,jib_tip_dy,jib_tip_dz,trolley_x,trolley_y,trolley_z,"
           "rope_top_tension,rope_length,slew_angle,trolley_radius,energy,constraint_error,"
           "subdomains,tension_ratio,load_chart_ratio,warnings,full_order_steps,payload_landed,"
           "contact_force")


def row(s, full_order_steps):
    v = lambda p: [p.x, p.y, p.z]  # noqa: E731
    values = ([s.t] + v(s.payload) + v(s.payload_velocity) + v(s.cab_displacement) +
              v(s.jib_tip_displacement) + v(s.trolley) +
              [s.rope_top_tension, s.rope_length, s.slew_angle, s.trolley_radius, s.energy,
               s.constraint_error, s.subdomains, s.tension_ratio, s.load_chart_ratio,
               s.warnings, full_order_steps, int(s.payload_landed), s.contact_force] +
              list(getattr(s, "stresses", [])))
    return ",".join(repr(float(x)) if not isinstance(x, int) else str(x) for x in values)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bag")
    parser.add_argument("--series")
    parser.add_argument("--commands")
    parser.add_argument("--stats", action="store_true")
    a = parser.parse_args()
    try:
        bag = rosbag.Bag(a.bag)
    except Exception as e:  # rosbag raises several types for a bad file
        sys.exit("bag_to_series: %s: %s" % (a.bag, e))
    # full_order_steps is not in crane/state: it comes from the node's latest /diagnostics
    # (1 Hz) before each state, 0 before the first.
    states, commands, steps = [], [], 0
    for topic, msg, _ in bag.read_messages(
            topics=["/crane/state", "/crane/command_applied", "/diagnostics"]):
        if topic == "/diagnostics":
            for status in msg.status:
                for kv in status.values:
                    if kv.key == "full_order_steps":
                        steps = int(float(kv.value))
        elif topic == "/crane/state":
            states.append((msg, steps))
        else:
            commands.append(msg)
    bag.close()
    if not states:
        sys.exit("bag_to_series: %s holds no /crane/state" % a.bag)
    states.sort(key=lambda s: s[0].t)
    if a.series:
        with open(a.series, "w") as f:
            # The hot spots' stresses after contact_force, as crane_sim run writes them.
            names = list(getattr(states[0][0], "stress_names", []))
            f.write(COLUMNS + "".join(",stress_" + n for n in names) + "\n")
            for s, steps in states:
                f.write(row(s, steps) + "\n")
    states = [s for s, _ in states]
    if a.commands:
        # Commands applied at the same simulated time (one sent during a pause and the start's
        # own): the last applied is the one in force, and a schedule's times must increase.
        last = {}
        for c in commands:  # in the order the node applied them (the bag's order)
            last[c.header.stamp.to_sec()] = c
        entries = ["{t: %r, slew_rate: %r, trolley_speed: %r, hoist_speed: %r}" %
                   (t, c.slew_rate, c.trolley_speed, c.hoist_speed)
                   for t, c in sorted(last.items())]
        with open(a.commands, "w") as f:
            f.write("[" + ", ".join(entries) + "]\n")
    if a.stats:
        cost = [s.step_compute_time for s in states if s.step_compute_time > 0]
        rtf = [s.real_time_factor for s in states if s.real_time_factor > 0]
        print("states,%d" % len(states))
        print("applied_commands,%d" % len(commands))
        print("sim_s,%g" % (states[-1].t - states[0].t))
        print("model,%s" % states[0].model)
        if cost:
            print("median_step_cost_s,%.3g" % statistics.median(cost))
        if rtf:
            print("median_real_time_factor,%.3g" % statistics.median(rtf))
    return 0


if __name__ == "__main__":
    sys.exit(main())
