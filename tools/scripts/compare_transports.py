#!/usr/bin/env python3
"""Where-am-I in one process and on DDS: do they sense the same edges and reach the same pose?

For each seed, the same start is run twice with the same configuration files:
  - in process: `stickrep-whereami --seed S -N 1` (the components on the in-process executor,
    simulated clock);
  - deployed: the virtual robot and the six processes started on their own, on one DDS domain,
    at real time (real_time_factor 1), until the executive has the pose.
The deployed run's sensed sequence is the localizer's "sensed:" log line when it declared the
pose, and its pose is the virtual robot's "pose recovered" line (judged on the truth there).

Usage: tools/scripts/compare_transports.py --bin build/bin --seeds 1-20 [--map maps/M.yaml --ring R]
Prints one line per seed and the agreement; --json writes every pair.
"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

PROCESSES = ["stickrep-sonar", "stickrep-camera", "stickrep-locomotion", "stickrep-landmark",
             "stickrep-localizer", "stickrep-executive"]
POSE_RE = re.compile(
    r"pose recovered after (\d+) edges, ([\d.]+) ft, ([\d.]+) s simulated.*?: ring '([^']*)' "
    r"edge (\d+) (forward|backward); truth ring '([^']*)' edge (\d+) (forward|backward): "
    r"(CORRECT|INCORRECT)")
SENSED_RE = re.compile(r"sensed: (.*)$")


def seeds_of(text):
    out = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            out.extend(range(int(a), int(b) + 1))
        else:
            out.append(int(part))
    return out


def in_process(args, seed, work):
    path = os.path.join(work, f"inproc_{seed}.json")
    cmd = [os.path.join(args.bin, "stickrep-whereami"), "--config-dir", args.config_dir,
           "--seed", str(seed), "-N", "1", "--threads", "1", "--json", path]
    if args.map:
        cmd += ["--map", args.map]
    if args.ring:
        cmd += ["--ring", args.ring]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        run = json.load(f)["runs"][0]
    first = run["first"]
    pose = None if first is None else (first["ring"], first["edge"], first["forward"])
    return {"sensed": run["sensed"].strip(), "pose": pose,
            "correct": bool(first and first["correct"]),
            "edges": first["edges_sensed"] if first else None,
            "distance_ft": first["distance_ft"] if first else None}


def deployed(args, seed, work):
    system = os.path.abspath(os.path.join(args.config_dir, "system.yaml"))
    if args.map:
        system = os.path.join(work, "system.yaml")
        with open(os.path.join(args.config_dir, "system.yaml")) as f:
            text = f.read()
        cfg = os.path.abspath(args.config_dir)
        text = re.sub(r"map_file:.*", f"map_file: {os.path.abspath(args.map)}", text)
        text = re.sub(r"qos_file:.*", f"qos_file: {cfg}/qos.yaml", text)
        text = re.sub(r"robot_file:.*", f"robot_file: {cfg}/robot.yaml", text)
        with open(system, "w") as f:
            f.write(text)
    common = ["--system", system, "--domain", str(args.domain)]
    logs = {}
    procs = {}

    def start(exe, extra):
        log = open(os.path.join(work, f"{exe}_{seed}.log"), "w")
        logs[exe] = log.name
        procs[exe] = subprocess.Popen([os.path.join(args.bin, exe)] + common + extra,
                                      stdout=log, stderr=subprocess.STDOUT)

    vr = ["--set", f"seed={seed}", "--set", "real_time_factor=1"]
    if args.ring:
        vr += ["--set", f"ring_id={args.ring}"]
    start("stickrep-virtual-robot", vr)
    for exe in PROCESSES:
        start(exe, ["--set", "exit_when_localized=true"] if exe == "stickrep-executive" else [])
    deadline = time.time() + args.timeout_s
    while time.time() < deadline and procs["stickrep-executive"].poll() is None:
        time.sleep(0.5)
    for p in procs.values():
        if p.poll() is None:
            p.send_signal(signal.SIGINT)
    for p in procs.values():
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
    sensed, pose, correct, edges, feet = "", None, False, None, None
    with open(logs["stickrep-localizer"]) as f:
        for line in f:
            m = SENSED_RE.search(line)
            if m:
                sensed = m.group(1).strip()
                break
    with open(logs["stickrep-virtual-robot"]) as f:
        for line in f:
            m = POSE_RE.search(line)
            if m:
                edges, feet = int(m.group(1)), float(m.group(2))
                pose = (m.group(4), int(m.group(5)), m.group(6) == "forward")
                correct = m.group(10) == "CORRECT"
                break
    return {"sensed": sensed, "pose": pose, "correct": correct, "edges": edges,
            "distance_ft": feet}


def tokens(sensed):
    """The sensed sequence as (code, metric) pairs: 'wall:45' -> ('wall', 45), 'door36' ->
    ('door36', None)."""
    out = []
    for t in sensed.split():
        code, _, metric = t.partition(":")
        out.append((code, float(metric) if metric else None))
    return out


def agreement(a, b, tolerance_in):
    """'same': the same edges, lengths within tolerance_in; 'same_codes': the same edges
    whatever the lengths; the first edge is partial, so its length is compared only as an
    edge."""
    ta, tb = tokens(a), tokens(b)
    if not ta or [c for c, _ in ta] != [c for c, _ in tb]:
        return {"same_codes": False, "same": False}
    close = all(i == 0 or ma is None or abs(ma - mb) <= tolerance_in
                for i, ((_, ma), (_, mb)) in enumerate(zip(ta, tb)))
    return {"same_codes": True, "same": close}


def summarize(pairs, tolerance_in):
    for p in pairs:
        p.update(agreement(p["in_process"]["sensed"], p["deployed"]["sensed"], tolerance_in))
    n = len(pairs)
    count = lambda f: sum(1 for p in pairs if f(p))
    print(f"\n{n} seeds: same sensed edges (lengths within {tolerance_in:g} in, the partial "
          f"first edge by kind only) {count(lambda p: p['same'])}; same edges whatever the "
          f"lengths {count(lambda p: p['same_codes'])}; identical text "
          f"{count(lambda p: p['same_sequence'])}; same pose {count(lambda p: p['same_pose'])}; "
          f"correct in process {count(lambda p: p['in_process']['correct'])}, deployed "
          f"{count(lambda p: p['deployed']['correct'])}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--config-dir", default="configs")
    ap.add_argument("--seeds", default="1-20")
    ap.add_argument("--map", default="")
    ap.add_argument("--ring", default="")
    ap.add_argument("--domain", type=int, default=61)
    ap.add_argument("--timeout-s", type=float, default=300.0)
    ap.add_argument("--json", default="")
    ap.add_argument("--tolerance-in", type=float, default=6.0)
    ap.add_argument("--from-json", default="", help="summarize a saved --json instead of running")
    args = ap.parse_args()
    if args.from_json:
        with open(args.from_json) as f:
            pairs = json.load(f)
        for p in pairs:
            if not p["same_sequence"]:
                print(f"seed {p['seed']}:\n    in process: {p['in_process']['sensed']}\n"
                      f"    deployed:   {p['deployed']['sensed']}")
        summarize(pairs, args.tolerance_in)
        return 0
    seeds = seeds_of(args.seeds)
    pairs = []
    with tempfile.TemporaryDirectory(prefix="stickrep_compare_") as work:
        for seed in seeds:
            a = in_process(args, seed, work)
            b = deployed(args, seed, work)
            same_seq = a["sensed"] == b["sensed"] and a["sensed"] != ""
            same_pose = a["pose"] is not None and a["pose"] == b["pose"]
            pairs.append({"seed": seed, "in_process": a, "deployed": b,
                          "same_sequence": same_seq, "same_pose": same_pose})
            print(f"seed {seed:3d}: in process {a['pose']} {a['edges']} edges "
                  f"{'CORRECT' if a['correct'] else 'WRONG'}; deployed {b['pose']} {b['edges']} "
                  f"edges {'CORRECT' if b['correct'] else 'WRONG'}; same sequence {same_seq}, "
                  f"same pose {same_pose}", flush=True)
            if not same_seq:
                print(f"    in process: {a['sensed']}\n    deployed:   {b['sensed']}", flush=True)
    summarize(pairs, args.tolerance_in)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(pairs, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
