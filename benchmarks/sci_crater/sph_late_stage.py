"""SPH alone to the crater's late stage: SPHImpact with the late-stage scheme (LateStageTime,
LateStageSoundSpeed) and a DomainRadius for the fast ejecta, measured by CraterProfile at every
output and compared with the Housen & Holsapple (2011) pi-scaling diameter for the same
impactor, target and gravity. Prints one line per output (crater diameter at the pre-impact
level, depth, the depth of the impactor's centre of mass, rim diameter, kinetic energy of the
slow material, the largest speed under the pre-impact surface against the late-stage sound speed
in force, seconds) and a summary.

    scripts/pvbatch benchmarks/sci_crater/sph_late_stage.py            # 2 kg at 2 km/s, g = 9.81, ~8 min
    scripts/pvbatch benchmarks/sci_crater/sph_late_stage.py --help
"""

import argparse
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from craterkit import fetch, fetch_stage, field_value, impactor_depth, load_plugin, property_settings, sci  # noqa: E402


def say(message):
    sys.stderr.write(message + "\n")
    sys.stderr.flush()


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--impactor-material", default="regolith",
                   help="the default (a 2 kg regolith-matrix sphere) is resolved by 2 particles on the target's lattice")
    p.add_argument("--impactor-mass", type=float, default=2.0, help="kg")
    p.add_argument("--impact-speed", type=float, default=2000.0, help="m/s")
    p.add_argument("--gravity", type=float, default=9.81, help="m/s^2")
    p.add_argument("--resolution", type=int, default=2, help="SPH particles across the impactor")
    p.add_argument("--target-radius", type=float, default=1.2, help="m (held in a rigid container)")
    p.add_argument("--domain-radius", type=float, default=2.5, help="m; beyond it particles fly ballistically")
    p.add_argument("--late-stage-time", type=float, default=1e-3, help="s")
    p.add_argument("--late-stage-sound-speed", type=float, default=50.0, help="m/s")
    p.add_argument("--end-time", type=float, default=0.3, help="s")
    p.add_argument("--interval", type=float, default=0.02, help="s between measurements")
    p.add_argument("--slow", type=float, default=5.0, help="m/s; the kinetic energy of material slower than this is printed")
    p.add_argument("--save", default="",
                   help="write the last output here (.vtp), a state examples/sci_crater.py --sph-state hands off")
    p.add_argument("--set", action="append", default=[], metavar="PROPERTY=VALUE",
                   help="any other SPHImpact property, e.g. --set FrictionAngle=25 --set TargetPorosity=0.4")
    args = p.parse_args()
    extra = property_settings(p, args.set)

    simple = load_plugin()
    sc = sci.scales(args.gravity, args.impactor_mass, args.impact_speed, args.impactor_material, "regolith",
                    extra.get("TargetPorosity", -1.0))
    d_pi, rho_imp, rho_bulk = sc.d_pi, sc.rho_impactor, sc.rho_bulk
    sph = simple.SPHImpact(ImpactorMaterial=args.impactor_material, ImpactorMass=args.impactor_mass,
                           ImpactSpeed=args.impact_speed, SurfaceGravity=args.gravity,
                           ParticlesAcrossImpactor=args.resolution, TargetRadius=args.target_radius,
                           TargetContainer=1, DomainRadius=args.domain_radius,
                           LateStageTime=args.late_stage_time, LateStageSoundSpeed=args.late_stage_sound_speed,
                           EndTime=args.end_time, OutputInterval=args.interval, KeptStates=0, **extra)
    profile = simple.CraterProfile(Input=sph)
    say(f"pi-scaling crater diameter: {d_pi:.3f} m (impactor density {rho_imp:g}, target {rho_bulk:.0f} kg/m^3, "
        f"g = {args.gravity:g} m/s^2)")
    start = time.time()
    rows = []
    for k in range(1, int(round(args.end_time / args.interval)) + 1):
        t = k * args.interval
        data = fetch_stage(sph, "SPH", t)
        v = vtk_to_numpy(data.GetPointData().GetArray("Velocity"))
        m = vtk_to_numpy(data.GetPointData().GetArray("Mass"))
        speed = np.sqrt((v * v).sum(1))
        slow = speed < args.slow
        ke_slow = 0.5 * float((m[slow] * speed[slow] ** 2).sum())
        # The flow under the pre-impact surface against the late-stage law's sound speed: the
        # law holds only while c is several times the flow speeds (docs/physics.md 2.8).
        z = vtk_to_numpy(data.GetPoints().GetData())[:, 2]
        buried = float(speed[z < 0.0].max()) if (z < 0.0).any() else 0.0
        c_late = field_value(data, "LateStageSoundSpeed", 0.0)
        imp_depth = impactor_depth(data)["centre_of_mass_m"]  # the crater forms around its track
        imp_depth = float("nan") if imp_depth is None else imp_depth
        profile.UpdatePipeline(t)
        fd = fetch(profile).GetFieldData()
        value = lambda name: fd.GetArray(name).GetValue(0) if fd.GetArray(name) else float("nan")  # noqa: E731
        row = (t, int(field_value(data, "Step")), value("CraterDiameter"), value("CraterDepth"),
               value("RimDiameter"), ke_slow, time.time() - start, imp_depth, buried, c_late)
        rows.append(row)
        say(f"t = {row[0]:.3f} s  step {row[1]:6d}  D = {row[2]:.3f} m ({row[2] / d_pi:.2f} of pi-scaling)  "
            f"depth {row[3]:.3f} m  impactor {row[7]:.3f} m deep  rim diameter {row[4]:.3f} m  slow KE {row[5]:.3g} J  "
            f"buried flow {row[8]:.3g} m/s, c {row[9]:.3g} m/s  {row[6]:.0f} s")
    last = rows[-1]
    if args.save:
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(args.save)
        writer.SetInputData(data)
        if not writer.Write():
            sys.exit(f"--save {args.save}: could not write")
        say(f"saved the state at t = {last[0]:g} s to {args.save}")
    say(f"\n{data.GetNumberOfPoints()} SPH particles; at {last[0]:.3f} s: D = {last[2]:.3f} m = "
        f"{last[2] / d_pi:.2f} x pi-scaling ({d_pi:.3f} m), depth {last[3]:.3f} m, depth/D {last[3] / last[2] if last[2] > 0 else float('nan'):.2f}, "
        f"impactor's centre of mass {last[7]:.3f} m deep; "
        f"{last[6]:.0f} s on {os.cpu_count()} cores")


main()
