#!/usr/bin/env python3
"""tools/scripts/edge_budget.py on a small trace in the form `stickrep-whereami --trace` prints."""
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "scripts",
                      "edge_budget.py")
spec = importlib.util.spec_from_file_location("edge_budget", SCRIPT)
edge_budget = importlib.util.module_from_spec(spec)
spec.loader.exec_module(edge_budget)

# Seed 7 starts on ring 'a' and goes on into ring 'c', where its pose is judged and declared;
# seed 8 never has the truth as its best place and is declared wrong; seed 9 is declared
# after 6 edges with a sequence of 2, begun again on the way.
TRACE = """\
seed    7  start ring 'a' edge 3 + 10.0 in, +1.0 in off the axis, heading +0.5 deg (seed 7)
            correct: CORRECT after 4 edges, 30.0 ft, 12.0 s: ring 'c' edge 3 fwd, truth edge 3 fwd
            sensed: wall:100 door36[plain] wall:46 door36[window]
            passed: wall:100[0] door36[1] <ring:c> wall:46[2] door36[3] wall:50[4] 
                1.0 s  localizer RECOVERING: newest door36[plain], best ring 'b' edge 5 fwd p=0.300, truth ring 'a' edge 1 (view edge 1) fwd: best place has posterior 0.3000
                2.0 s  localizer RECOVERING: newest wall:46, best ring 'c' edge 2 fwd p=0.900, truth ring 'c' edge 2 (view edge 2) fwd: best place has posterior 0.9000
                3.0 s  localizer LOCALIZED: newest door36[window], best ring 'c' edge 3 fwd p=0.999, truth ring 'c' edge 3 (view edge 3) fwd: best place has posterior 0.9990: pose recovered
seed    8  start ring 'a' edge 9 + 4.0 in, -2.0 in off the axis, heading -1.0 deg (seed 8)
            wrong: INCORRECT after 2 edges, 20.0 ft, 9.0 s: ring 'a' edge 1 fwd, truth edge 9 fwd
            sensed: wall:80 door40
            passed: wall:80[9] door36[10] wall:46[11] 
                1.0 s  localizer LOCALIZED: newest door40, best ring 'a' edge 1 fwd p=0.999, truth ring 'a' edge 10 (view edge 10) fwd: best place has posterior 0.9990: pose recovered
seed    9  start ring 'a' edge 20 + 4.0 in, -2.0 in off the axis, heading -1.0 deg (seed 9)
            correct: CORRECT after 6 edges, 50.0 ft, 30.0 s: ring 'a' edge 25 fwd, truth edge 25 fwd
            sensed: wall:46 door36
            passed: wall:80[20] door36[21] wall:46[22] door36[23] wall:46[24] door36[25] wall:46[26] 
                1.0 s  localizer LOCALIZED: newest door36, best ring 'a' edge 25 fwd p=0.999, truth ring 'a' edge 25 (view edge 25) fwd: best place has posterior 0.9990: pose recovered
"""


class EdgeBudgetTest(unittest.TestCase):
    def setUp(self):
        fd, self.path = tempfile.mkstemp(suffix=".log")
        with os.fdopen(fd, "w") as f:
            f.write(TRACE)

    def tearDown(self):
        os.unlink(self.path)

    def test_the_truth_is_judged_on_the_ring_it_is_seen_on(self):
        runs = edge_budget.read_runs(self.path)
        self.assertEqual([r["seed"] for r in runs], [7, 8, 9])
        # The best place names ring 'c' from the second estimate on, where the truth then is:
        # settled after 3 sensed edges, though the run started on ring 'a'.
        self.assertEqual(edge_budget.settled_at(runs[0]), 3)
        self.assertIsNone(edge_budget.settled_at(runs[1]))

    def test_a_ring_change_is_not_an_edge_passed(self):
        runs = edge_budget.read_runs(self.path)
        self.assertEqual(runs[0]["passed"], ["wall:100", "door36", "wall:46", "door36", "wall:50"])
        # The sensed edges (the partial first one left out) against the map edges passed: a
        # door's mark is not part of its kind, so nothing is misread in seed 7; seed 8 read
        # the 36 in door as 40.
        self.assertEqual(edge_budget.edit_distance(runs[0]["sensed"][1:], runs[0]["passed"][1:-1]), 0)
        self.assertEqual(edge_budget.edit_distance(runs[1]["sensed"][1:], runs[1]["passed"][1:-1]), 1)

    def test_the_report_counts_the_correct_runs_only(self):
        out = subprocess.run([sys.executable, SCRIPT, self.path], capture_output=True, text=True)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("3 runs read, 1 correct with a settled best place (1 correct left out: "
                      "their sequence was begun again on the way)", out.stdout)
        self.assertRegex(out.stdout, r"until the truth was the best place for good:\s+3\.00")

    def test_a_file_without_a_trace_is_refused_with_exit_code_2(self):
        with tempfile.NamedTemporaryFile("w", suffix=".log") as f:
            f.write("not a trace\n")
            f.flush()
            out = subprocess.run([sys.executable, SCRIPT, f.name], capture_output=True, text=True)
        self.assertEqual(out.returncode, 2)
        self.assertIn("no correct run with its trace", out.stderr)


if __name__ == "__main__":
    unittest.main()
