#!/usr/bin/env python3
"""The slow suite reports only what ran (tests/slow/validate.py), checked without running a case:

- a SCI case whose run crashes FAILs, though a passing summary.json of an earlier run lies in its
  folder (the run is made to crash for real: scripts/pvbatch finds no plugin);
- a summary older than the run, or missing a bed, is refused;
- the rows that used to be stated now assert: HCP smaller and shallower than RCP, each crater
  within 15 % of its own pi-scaling diameter, every v_a/v0 of the front-velocity case below 1.

    tests/slow/test_validate.py        (ctest: unit.slow_suite_reports_only_what_ran)
"""

import json
import os
import subprocess
import sys
import tempfile
import time
import types
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import validate  # noqa: E402


def report(diameter, depth, rim=18.0, gravity=1.5e-4, density=1190.0):
    """A run's report with the fields the cases read (the SCI impact into regolith)."""
    return {"crater_diameter_m": diameter, "crater_depth_m": depth, "rim_diameter_m": rim,
            "gravity_m_s2": gravity, "diameter_over_pi_scaling": 1.0,
            "impactor": {"mass_kg": 2.0, "speed_m_s": 2000.0, "density_kg_m3": 8960.0},
            "target": {"bulk_density_kg_m3": density}}


def write_summary(path, rows):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump({"rows": [{"packing": pk, "particles": n, "report": r} for pk, n, r in rows],
                   "checks": [True]}, f)


class CrashedRunFails(unittest.TestCase):
    def test_a_crashed_sci_run_fails_despite_an_old_passing_summary(self):
        with tempfile.TemporaryDirectory() as build:
            old = os.path.join(build, "slow", validate.RYUGU_DIR, "summary.json")
            write_summary(old, [("RCP", 30000, report(14.5, 2.3))])  # would pass every row
            results = os.path.join(build, "validation.md")
            env = dict(os.environ, CRATERKIT_BUILD_DIR=os.path.join(build, "no-plugin-here"))
            p = subprocess.run([sys.executable, os.path.join(HERE, "validate.py"), "sci_ryugu_run",
                                "--build", build, "--results", results], env=env, text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
            self.assertNotEqual(p.returncode, 0, p.stdout)
            self.assertIn("FAIL: sci_ryugu_run: the run", p.stdout)
            self.assertIn("exited with 3", p.stdout)
            self.assertFalse(os.path.exists(old), "the earlier run's summary must be gone")
            with open(results) as f:
                table = f.read()
            self.assertIn("| FAIL |", table)
            self.assertNotIn("| PASS |", table)


class OnlyFreshSummaries(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "summary.json")
        write_summary(self.path, [("RCP", 30000, report(14.0, 2.0))])

    def tearDown(self):
        self.dir.cleanup()

    def test_a_summary_written_by_the_run_is_read(self):
        reports = validate.fresh_reports(self.path, time.time() - 5.0, [("RCP", 30000)])
        self.assertEqual(reports[("RCP", 30000)]["crater_diameter_m"], 14.0)

    def test_a_summary_older_than_the_run_is_refused(self):
        past = time.time() - 3600.0
        os.utime(self.path, (past, past))
        with self.assertRaisesRegex(validate.RunFailed, "older than the run"):
            validate.fresh_reports(self.path, time.time(), [("RCP", 30000)])

    def test_a_summary_missing_a_bed_is_refused(self):
        with self.assertRaisesRegex(validate.RunFailed, "no result for"):
            validate.fresh_reports(self.path, 0.0, [("RCP", 30000), ("HCP", 30000)])

    def test_a_missing_ryugu_run_is_a_failure_not_a_crash(self):
        args = types.SimpleNamespace(build=self.dir.name)
        with self.assertRaisesRegex(validate.RunFailed, "missing"):
            validate.ryugu_report(args, "no_such_case")


class RowsThatCanFail(unittest.TestCase):
    """Each case's verdict follows the figures: the same case passes on good figures and fails
    on bad ones (sci_run and the pvbatch runs replaced by canned reports)."""

    def setUp(self):
        self.saved = {name: getattr(validate, name) for name in ("sci_run", "ryugu_report", "hvi_debris_cloud_run")}
        self.args = types.SimpleNamespace(build="unused", resume=False, quick=False)

    def tearDown(self):
        for name, fn in self.saved.items():
            setattr(validate, name, fn)

    def verdicts(self, case):
        return [row.ok for row in case(self.args)]

    def test_rcp_vs_hcp(self):
        for hcp, ok in ((report(10.3, 2.66), True), (report(14.0, 5.0), False)):
            validate.sci_run = lambda *a, hcp=hcp: {("RCP", 30000): report(13.8, 4.39), ("HCP", 30000): hcp}
            self.assertEqual(self.verdicts(validate.rcp_vs_hcp), [ok, ok])

    def test_sci_crater_ryugu_reads_the_shared_run(self):
        validate.ryugu_report = lambda *a: report(14.0, 2.5)
        self.assertEqual(self.verdicts(validate.sci_crater_ryugu), [True, True, True])
        validate.ryugu_report = lambda *a: report(14.0, 4.0)  # too deep: the depth row fails alone
        self.assertEqual(self.verdicts(validate.sci_crater_ryugu), [True, False, True])

    def test_pi_scaling_against_each_crater_own_d_pi(self):
        d_pi = validate.own_pi_scaling_diameter(report(1.0, 0.2, gravity=1000.0))
        self.assertAlmostEqual(d_pi, 1.0, delta=0.05)  # the SCI impact at g = 1000 m/s^2
        for factor, ok in ((1.0, True), (0.8, False)):
            validate.sci_run = lambda a, name, g, n, *rest, f=factor: {
                ("RCP", n[0]): report(f * validate.own_pi_scaling_diameter(report(1, 1, gravity=g)), 0.2, gravity=g)}
            validate.ryugu_report = lambda *a: report(14.0, 4.0)
            self.assertEqual(self.verdicts(validate.pi_scaling), [ok, ok, True])

    def test_hvi_front_velocity_bounded_by_the_impact_speed(self):
        layers = (1.1, 1.05, 1.0)  # the lattice series that follows (test_hvi_front_layers)
        for speeds, ok in (((0.95, 0.9, 0.85, 0.8), True), ((1.12, 0.9, 0.85, 0.8), False)):
            it = iter(speeds + layers)

            def fake(*a, it=it):
                va = next(it)
                one = {"va_over_v0_measured": va, "F_measured": 0.5, "largest_cloud_fragment_fraction": 0.3,
                       "front_sharpness": 0.15}
                return {"particles": 1000, "models": {"None": one, "ShockViscosity": dict(one)}}

            validate.hvi_debris_cloud_run = fake
            rows = validate.hvi_front_velocity(self.args)
            for model in validate.MODELS:
                checked = [row.ok for row in rows if row.quantity.startswith("v_a/v0 at t/D = ")
                           and f", {model} (" in row.quantity]
                self.assertEqual(len(checked), 4)
                self.assertEqual(checked[0], ok)
                self.assertTrue(all(checked[1:]))
            self.assertTrue(all(row.ok is None for row in rows if row.tolerance == "stated"))

    def test_hvi_front_layers_must_fall_as_the_plate_is_resolved(self):
        for speeds, ok in (((1.12, 1.08, 1.05), True), ((1.12, 1.08, 1.09), False)):
            it = iter(speeds)

            def fake(*a, it=it):
                one = {"va_over_v0_measured": next(it)}
                return {"particles": 1000, "models": {"None": one, "ShockViscosity": dict(one)}}

            validate.hvi_debris_cloud_run = fake
            rows = validate.hvi_front_layers(self.args)
            checked = [row.ok for row in rows if row.tolerance == "monotonic"]
            self.assertEqual(checked, [ok, ok])
            self.assertEqual(sum(row.tolerance == "stated" for row in rows), 6)

if __name__ == "__main__":
    unittest.main(verbosity=2)
