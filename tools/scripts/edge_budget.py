#!/usr/bin/env python3
"""Where the Where-am-I runs' sensed edges go, read from `stickrep-whereami --trace`.

For every run that declared a correct pose:
  - the edges it declared after (the localizer's sequence);
  - the edges until the truth became the filter's best place for good (on every later
    estimate the best place is the true ring, direction and edge or a neighbour): the
    ambiguity of the map and the misreads;
  - the edges after that, while the posterior of the right place grew to the threshold;
  - the corners among the sensed edges, and the partial first edge (always one);
  - how many sensed edges were not read as the map has them: the edit distance, on edge
    kinds (walls by kind, doors by class, corners), between the sensed edges and the map
    edges the robot passed, the partial first edge and the edge it is in left out.
A run whose sequence was begun again on the way (it holds fewer edges than the pose was
declared after: an open end, a pose given up) is left out and counted.

Usage: stickrep-whereami --seed 1301 -N 200 --trace > trace.log
       tools/scripts/edge_budget.py trace.log
"""
import re
import statistics
import sys

START_RE = re.compile(r"seed\s+(\d+)\s+start ring '(\S+)'")
RESULT_RE = re.compile(r"(correct|wrong): .*after (\d+) edges")
ESTIMATE_RE = re.compile(
    r"localizer (?:RECOVERING|LOCALIZED): newest (\S+), best ring '(\S+)' edge (\d+) (\w+) "
    r"p=[\d.]+, truth ring '(\S+)' edge (\d+) \(view edge \d+\) (\w+)")


def kind(token):
    # A door's mark as sensed ("door36[plain]") is not part of its kind: the map edges
    # passed carry none.
    return "wall" if token.startswith("wall") else re.sub(r"\[[a-z]+\]$", "", token)


def edit_distance(a, b):
    row = list(range(len(b) + 1))
    for i, x in enumerate(a, 1):
        diagonal, row[0] = row[0], i
        for j, y in enumerate(b, 1):
            best = min(row[j] + 1, row[j - 1] + 1, diagonal + (kind(x) != kind(y)))
            diagonal, row[j] = row[j], best
    return row[-1]


def read_runs(path):
    runs, run = [], None
    with open(path, errors="replace") as f:
        for line in f:
            m = START_RE.match(line)
            if m:
                run = {"seed": int(m.group(1)), "ring": m.group(2), "estimates": []}
                runs.append(run)
                continue
            if run is None:
                continue
            m = RESULT_RE.search(line)
            if m and "declared" not in run:
                run["correct"], run["declared"] = m.group(1) == "correct", int(m.group(2))
            if line.strip().startswith("sensed: "):
                run["sensed"] = line.split(":", 1)[1].split()
            elif line.strip().startswith("passed: "):
                # A ring change ("<ring:x>") is a mark in the trace, not an edge passed.
                run["passed"] = [re.sub(r"\[\d+\]$", "", t)
                                 for t in line.split(":", 1)[1].split() if not t.startswith("<ring:")]
            m = ESTIMATE_RE.search(line)
            if m:
                run["estimates"].append((m.group(1), m.group(2), int(m.group(3)), m.group(4),
                                         m.group(5), int(m.group(6)), m.group(7)))
    return [r for r in runs if "declared" in r and "sensed" in r and "passed" in r]


def settled_at(run):
    """Edges sensed when the best place became the truth for good (None if it never did)."""
    at, marks = -1, []
    for newest, ring, edge, direction, truth_ring, truth, truth_direction in run["estimates"]:
        j = at + 1
        while j < len(run["sensed"]) and run["sensed"][j] != newest:
            j += 1
        if j < len(run["sensed"]):
            at = j
        right = ring == truth_ring and abs(edge - truth) <= 1 and direction == truth_direction
        marks.append((at + 1, right))
    settled = None
    for edges, right in reversed(marks):
        if not right:
            break
        settled = edges
    return settled


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    try:
        runs = read_runs(sys.argv[1])
    except OSError as e:
        print(f"{sys.argv[1]}: cannot read it ({e.strerror})", file=sys.stderr)
        sys.exit(2)
    rows, restarted = [], 0
    for r in runs:
        # A sequence that holds fewer edges than the pose was declared after was begun again
        # on the way (at an open end, or after a pose given up): it does not cover the run.
        if sum(not t.startswith("<") for t in r["sensed"]) < r["declared"]:
            restarted += r["correct"]
            continue
        settled = settled_at(r)
        if r["correct"] and settled is not None:
            rows.append((r["declared"], settled, sum(t.startswith("<") for t in r["sensed"]),
                         edit_distance(r["sensed"][1:], r["passed"][1:-1]), len(r["sensed"]) - 1))
    if not rows:
        print(f"{sys.argv[1]}: no correct run with its trace (stickrep-whereami --trace output?)"
              + (f"; {restarted} correct runs left out, their sequence begun again on the way"
                 if restarted else ""), file=sys.stderr)
        sys.exit(2)
    mean = lambda i: statistics.mean(row[i] for row in rows)
    print(f"{len(runs)} runs read, {len(rows)} correct with a settled best place"
          + (f" ({restarted} correct left out: their sequence was begun again on the way)"
             if restarted else ""))
    print(f"edges when the pose was declared:                 {mean(0):6.2f} (median {statistics.median(r[0] for r in rows)})")
    print(f"  the partial first edge:                          {1:6.2f}")
    print(f"  until the truth was the best place for good:     {mean(1):6.2f} (median {statistics.median(r[1] for r in rows)})")
    print(f"  after it, the posterior growing to the threshold:{mean(0) - mean(1):6.2f}")
    print(f"corners among the sensed edges:                   {mean(2):6.2f}")
    print(f"sensed edges not read as the map has them:        {mean(3):6.2f} of {mean(4):.2f} "
          f"(first edge left out)")


if __name__ == "__main__":
    main()
