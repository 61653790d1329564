#!/usr/bin/python3
"""Seeded draws of scenes nobody ships, for a robustness sweep (docs/accuracy-vs-time.md,
"Scenes nobody ships"): each draw is one of the shipped T8036 scenes of its kind with its payload,
radius, rope length, duration, structure model, mesh, rigging and falls drawn, and what the kind
adds (swing, friction, the load's offset, wind and gusts, a random command seed, a throw; `pick`
runs the shipped pick-swing-place cycle's 70 s from a drawn radius, perhaps off-centre;
`windland` a lift-off, set-down or that cycle in wind; `drag` a landed load under a slewing
crane or a moving trolley, perhaps while reeling in; `release` a load released from its held
equilibrium at 40 to 60 deg, whose rope slackens past 45).

    scripts/draw_scenes.py SEED COUNT [--kinds hang,landed,...] > LIST
    scripts/reduced_vs_full.sh LIST 2

prints one line per draw, `name scene duration --set key=value ...`, the list format of
scripts/reduced_vs_full.sh. The same seed and kinds give the same draws. Draws may ask what the
crane refuses (a load over the chart is run and warned about; a rope that does not reach a
landed load, or one that would start inside the ground, exits 2 naming the key): the sweep
reports those as they come.
"""
import argparse
import random

KINDS = ("hang", "landed", "lower", "stress", "throw", "offset", "wind", "random", "pick",
         "windland", "drag", "release")
DEFAULT_KINDS = "hang,hang,landed,lower,stress,throw"


def draw(rng, kind):
    """(scene, duration, overrides) of one draw of `kind`."""
    o = {}
    mass = round(rng.uniform(500, 12500))
    radius = round(rng.uniform(5, 60), 1)
    length = round(rng.uniform(8, 62), 2)
    o["payload.mass"] = mass
    o["trolley.radius"] = radius
    o["rope.length"] = length
    o["duration"] = round(rng.uniform(6, 15), 1)
    o["structure.model"] = rng.choice(["modal", "modal", "rigid"])
    o["rope.elements"] = rng.choice([30, 60, 60, 90])
    if rng.random() < 0.3:
        o["hook.rigging_length"] = rng.choice([2, 4])
    if rng.random() < 0.2:
        o["rope.falls"] = rng.choice([2, 4])
    if kind == "hang":  # a hanging load under operation, perhaps released from a swing
        scene = rng.choice(["t8036_operator_cycle", "t8036_slew90", "t8036_trolley_80_to_30",
                            "t8036_hoist_60_20_50", "t8036_combination1"])
        if scene == "t8036_trolley_80_to_30":
            o.pop("trolley.radius")
        if scene == "t8036_hoist_60_20_50":
            o.pop("rope.length")
        if rng.random() < 0.5:
            o["initial.swing_deg"] = round(rng.uniform(0, 35), 1)
    elif kind == "landed":  # a lift-off from a landed start
        scene = rng.choice(["t8036_lift_off_fast", "t8036_lift_off_slow", "t8036_off_centre_lift"])
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        o.pop("rope.length")
    elif kind == "lower":  # a set-down
        scene = "t8036_set_down"
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        o.pop("rope.length")
    elif kind == "release":  # released from its held equilibrium at 40 to 60 deg (slack past 45)
        scene = "t8036_combination1"
        o["initial.swing_deg"] = round(rng.uniform(40, 60), 1)
        o["duration"] = round(rng.uniform(10, 20), 1)
    elif kind == "stress":  # a stress-free release from an anchor
        scene = "hard_stress_free_heavy"
        o = {k: v for k, v in o.items()
             if k in ("payload.mass", "rope.length", "duration", "rope.elements")}
    elif kind == "offset":  # a lift-off with the load up to 4 m off the trolley's vertical
        scene = "t8036_off_centre_lift"
        o["initial.payload_offset"] = "[%.1f,%.1f]" % (rng.uniform(-4, 4), rng.uniform(-4, 4))
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        o.pop("rope.length")
    elif kind == "wind":
        scene = rng.choice(["t8036_wind", "t8036_slew90", "t8036_operator_cycle"])
        o["wind.speed"] = round(rng.uniform(2, 25), 1)
        o["wind.direction_deg"] = round(rng.uniform(0, 360))
        if rng.random() < 0.5:
            o["wind.gust.intensity"] = round(rng.uniform(0.05, 0.3), 2)
    elif kind == "pick":  # the whole pick-swing-place cycle: lift off, hoist, slew, lower, set down
        scene = "t8036_pick_and_place"
        o["trolley.radius"] = round(rng.uniform(10, 45), 1)  # the cycle moves it 15 m out
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        if rng.random() < 0.3:
            o["initial.payload_offset"] = "[%.1f,%.1f]" % (rng.uniform(-2, 2), rng.uniform(-2, 2))
        o.pop("rope.length")
        o["duration"] = 70.0
    elif kind == "windland":  # a lift-off, set-down or pick in wind, perhaps gusty
        scene = rng.choice(["t8036_lift_off_slow", "t8036_off_centre_lift", "t8036_set_down",
                            "t8036_pick_and_place"])
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        o.pop("rope.length")
        if scene == "t8036_pick_and_place":
            o["trolley.radius"] = round(rng.uniform(10, 45), 1)
            o["duration"] = 70.0
        o["wind.speed"] = round(rng.uniform(2, 20), 1)
        o["wind.direction_deg"] = round(rng.uniform(0, 360))
        if rng.random() < 0.5:
            o["wind.gust.intensity"] = round(rng.uniform(0.05, 0.3), 2)
    elif kind == "drag":  # slewing or moving the trolley over a landed load, hoisting or not
        scene = rng.choice(["t8036_lift_off_slow", "t8036_off_centre_lift"])
        o["ground.friction"] = round(rng.uniform(0, 1), 2)
        o.pop("rope.length")
        o["trolley.radius"] = round(rng.uniform(10, 45), 1)
        move = ("slew_rate: %.3f" % rng.uniform(-0.04, 0.04) if rng.random() < 0.5 else
                "trolley_speed: %.2f" % rng.uniform(-0.5, 0.5))
        hoist = ", hoist_speed: %.2f" % -rng.uniform(0.1, 0.8) if rng.random() < 0.5 else ""
        stop = round(rng.uniform(3, 8), 1)
        o["commands"] = "[{t: 0, %s%s}, {t: %s, slew_rate: 0, trolley_speed: 0, hoist_speed: 0}]" % (
            move, hoist, stop)
        o["duration"] = round(rng.uniform(12, 20), 1)
    elif kind == "random":  # seeded random operator commands
        scene = "hard_random_commands"
        o["random_commands.seed"] = rng.randrange(1000)
        o["random_commands.hoist"] = rng.choice(["true", "false"])
        o.pop("rope.length")
        o.pop("trolley.radius")
    else:  # throw: the payload thrown up, the rope slack and snatching
        scene = "hard_slack_throw"
        o["initial.payload_velocity"] = "[0,0,%.1f]" % rng.uniform(0.5, 3)
        o["duration"] = round(rng.uniform(3, 6), 1)
    duration = o.pop("duration")
    return scene, duration, o


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("seed", type=int)
    p.add_argument("count", type=int)
    p.add_argument("--kinds", default=DEFAULT_KINDS,
                   help="comma-separated, drawn uniformly (repeat one to weight it): " +
                   ", ".join(KINDS) + " (default %(default)s)")
    a = p.parse_args()
    kinds = a.kinds.split(",")
    bad = [k for k in kinds if k not in KINDS]
    if bad or a.count < 0:
        p.error("unknown kind(s) %s" % ", ".join(bad) if bad else "count must be >= 0")
    rng = random.Random(a.seed)
    for i in range(a.count):
        kind = rng.choice(kinds)
        scene, duration, o = draw(rng, kind)
        # (a value with blanks is quoted for the list's reader, xargs)
        sets = " ".join(('--set "%s=%s"' if " " in str(v) else "--set %s=%s") % (k, v)
                        for k, v in o.items())
        print("d%d_%02d_%s %s %s %s" % (a.seed, i, kind, scene, duration, sets))


if __name__ == "__main__":
    main()
