#!/usr/bin/python3
"""Campaigns of crane_sim runs (docs/campaigns.md), two jobs in one file:

  campaign.py expand CAMPAIGN.yaml [RESULTS.csv]
      one line per run of the campaign (scene x the product of the grid's values), as
      id<TAB>scene<TAB>override<TAB>override...; runs whose id is already in RESULTS.csv are
      left out (a second call runs only what is missing).
  campaign.py run LINE
      run one expanded line with crane_sim and print its CSV row (no header).
  campaign.py header
      the CSV header.
  campaign.py summary RESULTS.csv
      the usage over every run of RESULTS.csv: lifts, k_Q, per hot spot the damage, its rate
      per simulated hour and the hours to D = 1 at that rate (docs/fatigue.md "Campaigns").

scripts/campaign.sh drives these with GNU parallel on local cores or ssh hosts.
"""
import csv
import hashlib
import io
import itertools
import math
import os
import random
import socket
import subprocess
import sys
import tempfile
import time

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COLUMNS = ["id", "scene", "overrides", "exit_status", "wall_s", "sim_s", "max_swing_deg",
           "max_tension_ratio", "max_load_chart_ratio", "warnings", "lifts", "k_q", "max_phi_2",
           "damage", "message", "host"]


class CampaignError(Exception):
    pass


def crane_sim():
    """The crane_sim binary: CRANE_SIM, else the catkin workspace's, else the core build's."""
    for p in (os.environ.get("CRANE_SIM", ""),
              os.path.join(ROOT, "build/ws/devel/lib/crane_twin/crane_sim"),
              os.path.join(ROOT, "build/core/crane_sim")):
        if p and os.access(p, os.X_OK):
            return p
    raise CampaignError("no crane_sim binary (build first: scripts/build.sh, or set CRANE_SIM)")


def scene_path(campaign_file, name):
    if "/" in name or name.endswith(".yaml"):
        return name if os.path.isabs(name) else os.path.normpath(
            os.path.join(os.path.dirname(os.path.abspath(campaign_file)), name))
    return os.path.join(ROOT, "config", "scenes", name + ".yaml")


def value_text(v):
    """A YAML value as crane_sim's --set takes it (flow style, one line)."""
    if isinstance(v, str):
        return v
    return yaml.safe_dump(v, default_flow_style=True, width=10**6).strip().removesuffix("...").strip()


def expand(campaign_file):
    try:
        with open(campaign_file) as f:
            c = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        raise CampaignError(f"{campaign_file}: {e}")
    if not isinstance(c, dict):
        raise CampaignError(f"{campaign_file}: must be a map with scenes, set, grid")
    unknown = set(c) - {"scenes", "set", "grid", "duration", "samples"}
    if unknown:
        raise CampaignError(f"{campaign_file}: unknown key(s) {', '.join(sorted(unknown))}")
    scenes = c.get("scenes")
    if not isinstance(scenes, list) or not scenes or not all(isinstance(s, str) for s in scenes):
        raise CampaignError(f"{campaign_file}: 'scenes' must be a non-empty list of scene names")
    fixed = c.get("set", []) or []
    if not isinstance(fixed, list) or not all(isinstance(s, str) and "=" in s for s in fixed):
        raise CampaignError(f"{campaign_file}: 'set' must be a list of key=value strings")
    if "duration" in c:
        d = c["duration"]
        if not isinstance(d, (int, float)) or isinstance(d, bool) or not d > 0 or math.isinf(d):
            raise CampaignError(f"{campaign_file}: 'duration' must be a positive number of seconds")
        fixed = fixed + [f"duration={d}"]
    grid = c.get("grid", {}) or {}
    if not isinstance(grid, dict) or not all(isinstance(v, list) and v for v in grid.values()):
        raise CampaignError(f"{campaign_file}: 'grid' must map keys to non-empty lists of values")
    keys = list(grid)
    draws = samples(campaign_file, c.get("samples"))
    runs = []
    for scene in scenes:
        path = scene_path(campaign_file, scene)
        if not os.path.isfile(path):
            raise CampaignError(f"{campaign_file}: scene '{scene}': no file {path}")
        for combo in itertools.product(*(grid[k] for k in keys)):
            for draw in draws:
                overrides = fixed + [f"{k}={value_text(v)}" for k, v in zip(keys, combo)] + draw
                key = scene + "\0" + "\0".join(overrides)
                runs.append((hashlib.sha1(key.encode()).hexdigest()[:12], scene, overrides))
    return runs


def samples(campaign_file, spec):
    """The overrides of each run `samples:` draws (one empty draw without it): `count` runs,
    each key of `uniform` drawn from its [low, high] with Python's Mersenne Twister seeded by
    `seed`, 4 significant digits; the same file draws the same runs on every machine."""
    if spec is None:
        return [[]]
    where = f"{campaign_file}: samples"
    if not isinstance(spec, dict) or set(spec) - {"count", "seed", "uniform"}:
        raise CampaignError(f"{where}: must be a map with count, seed, uniform")
    count, seed, uniform = spec.get("count"), spec.get("seed", 1), spec.get("uniform")
    if not isinstance(count, int) or isinstance(count, bool) or count < 1:
        raise CampaignError(f"{where}.count: must be a positive integer")
    if not isinstance(seed, int) or isinstance(seed, bool):
        raise CampaignError(f"{where}.seed: must be an integer")
    if not isinstance(uniform, dict) or not uniform:
        raise CampaignError(f"{where}.uniform: must map scene keys to [low, high]")
    for k, b in uniform.items():
        if (not isinstance(b, list) or len(b) != 2
                or not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                           and math.isfinite(x) for x in b) or not b[0] < b[1]):
            raise CampaignError(f"{where}.uniform.{k}: must be [low, high] with low < high")
    rng = random.Random(seed)
    return [[f"{k}={float(f'{rng.uniform(b[0], b[1]):.4g}'):g}" for k, b in uniform.items()]
            for _ in range(count)]


def result_rows(results):
    """The rows of a results file, refused when its columns are not this script's."""
    with open(results, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != COLUMNS:
            raise CampaignError(f"{results}: its columns are not this campaign.py's (an older "
                                f"file?): start a new results file")
        return list(reader)


def done_ids(results):
    if not results or not os.path.isfile(results) or os.path.getsize(results) == 0:
        return set()
    return {row["id"] for row in result_rows(results) if row.get("id")}


def run(line):
    fields = line.rstrip("\n").split("\t")
    if len(fields) < 2:
        raise CampaignError(f"not an expanded campaign line: {line!r}")
    run_id, scene, overrides = fields[0], fields[1], fields[2:]
    row = dict.fromkeys(COLUMNS, "")
    row.update(id=run_id, scene=scene, overrides=" ".join(overrides), host=socket.gethostname())
    path = scene if (scene.startswith("/") or scene.endswith(".yaml")) else scene_path("", scene)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "series.csv")
        cmd = [crane_sim(), "run", path, "--quiet", "--out", out]
        for o in overrides:
            cmd += ["--set", o]
        start = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        row["exit_status"] = p.returncode
        row["wall_s"] = f"{time.monotonic() - start:.3f}"
        errors = [l for l in p.stderr.splitlines() if l.startswith("error")]
        row["message"] = errors[0] if errors else ""
        if os.path.isfile(out):
            summarise(out, row)
        usage(p.stdout, row)
    return row


def usage(stdout, row):
    """The usage block of crane_sim run's output (docs/cli.md): lifts, k_Q, the largest phi_2,
    and each hot spot's damage as blank-separated name=value."""
    lifts, kq, phi, damage = "", "", 0.0, []
    for line in stdout.splitlines():
        head, _, rest = line.partition(": ")
        fields = dict(f.split("=", 1) for f in rest.split() if "=" in f)
        if head == "usage":
            lifts, kq = fields.get("lifts", ""), fields.get("k_Q", "")
        elif head == "usage_lift":
            phi = max(phi, float(fields["phi_2"]))
        elif head == "usage_hot_spot":
            damage.append(f"{fields['name']}={fields['damage']}")
    row.update(lifts=lifts, k_q=kq, max_phi_2=f"{phi:.4g}" if lifts else "",
               damage=" ".join(damage))


def summary(results):
    """Usage over the runs of `results` that finished: lifts, k_Q (lift-weighted), per hot spot
    the damage summed, per simulated hour, and the hours to D = 1 at that rate."""
    if not os.path.isfile(results):
        raise CampaignError(f"{results}: no such file")
    rows, failed, runs, lifts, kq_sum, hours, damage = 0, 0, 0, 0, 0.0, 0.0, {}
    for r in result_rows(results):
        rows += 1
        if r["exit_status"] != "0":
            failed += 1
            continue
        if not r["lifts"]:
            continue
        runs += 1
        n = int(r["lifts"])
        lifts += n
        kq_sum += n * float(r["k_q"])
        hours += float(r["sim_s"]) / 3600.0
        for pair in r["damage"].split():
            name, value = pair.split("=", 1)
            damage[name] = damage.get(name, 0.0) + float(value)
    lines = [f"campaign: {rows} rows in {results}, {failed} with a non-zero exit status",
             f"campaign usage: {runs} runs, {hours:.4g} h simulated, {lifts} lifts, "
             f"k_Q {kq_sum / lifts if lifts else 0.0:.4g}"]
    for name, d in damage.items():
        rate = d / hours if hours > 0 else 0.0
        life = f"{1.0 / rate:.4g}" if rate > 0 else "inf"
        lines.append(f"campaign usage: {name} damage {d:.4g}, {rate:.4g} per hour, "
                     f"{life} h to D = 1")
    return lines


def summarise(series_csv, row):
    """The run's figures from its time series: the largest swing of the rope's chord from the
    vertical [deg], the largest tension and load-chart ratios, the OR of the warning bits."""
    swing, tension, chart, warnings, t = 0.0, 0.0, 0.0, 0, 0.0
    with open(series_csv, newline="") as f:
        for r in csv.DictReader(f):
            dx = float(r["payload_x"]) - float(r["trolley_x"])
            dy = float(r["payload_y"]) - float(r["trolley_y"])
            dz = float(r["payload_z"]) - float(r["trolley_z"])
            swing = max(swing, math.degrees(math.atan2(math.hypot(dx, dy), -dz)))
            tension = max(tension, float(r["tension_ratio"]))
            chart = max(chart, float(r["load_chart_ratio"]))
            warnings |= int(r["warnings"])
            t = float(r["t"])
    row.update(sim_s=f"{t:g}", max_swing_deg=f"{swing:.4g}", max_tension_ratio=f"{tension:.4g}",
               max_load_chart_ratio=f"{chart:.4g}", warnings=warnings)


def main(argv):
    try:
        if len(argv) >= 2 and argv[1] == "header":
            csv.writer(sys.stdout).writerow(COLUMNS)
        elif len(argv) in (3, 4) and argv[1] == "expand":
            skip = done_ids(argv[3] if len(argv) == 4 else None)
            for run_id, scene, overrides in expand(argv[2]):
                if run_id not in skip:
                    print("\t".join([run_id, scene_path(argv[2], scene)] + overrides))
        elif len(argv) == 3 and argv[1] == "summary":
            print("\n".join(summary(argv[2])))
        elif len(argv) == 3 and argv[1] == "run":
            row = run(argv[2])
            buf = io.StringIO()
            csv.writer(buf).writerow([row[c] for c in COLUMNS])
            sys.stdout.write(buf.getvalue())
        else:
            print(__doc__, file=sys.stderr)
            return 2
    except CampaignError as e:
        print(f"campaign: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
