"""Measures the crater in an SPHImpact checkpoint (.cksph) while its run goes on: writes the
state (without the container's particles) as a VTP file and prints the crater's diameter, depth,
rim diameter and rim height (CraterProfile against the surface at z = 0) and how deep the
impactor's material (Material 0) is. For long runs such as the SCI impact at Ryugu's gravity,
whose SPH stage takes hours before it hands off.

    scripts/pvbatch benchmarks/sci_crater/peek_sph_checkpoint.py CHECKPOINT [OUT.vtp]

The checkpoint is read by the plugin's own reader (the one ParaView opens .cksph files with);
the container's particles (Material 2) are left out.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from craterkit import fetch, field_value, impactor_depth, load_plugin  # noqa: E402


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    path = argv[0]
    out = argv[1] if len(argv) > 1 else os.path.splitext(path)[0] + "_peek.vtp"
    if not os.path.isfile(path):
        sys.exit(f"{path}: no such file")
    simple = load_plugin()
    try:
        reader = simple.OpenDataFile(path)
    except RuntimeError as e:
        sys.exit(f"{path}: {e}")
    raw = fetch(reader)
    if raw is None or raw.GetNumberOfPoints() == 0 or raw.GetPointData().GetArray("Material") is None:
        sys.exit(f"{path}: not a readable SPH checkpoint (see the message above)")
    # The impactor and the target (Materials 0 and 1), as particles (vertices) again.
    body = simple.ExtractSurface(Input=simple.Threshold(Input=reader, Scalars=["POINTS", "Material"],
                                                        LowerThreshold=0, UpperThreshold=1))
    simple.SaveData(out, proxy=body)
    state = fetch(body)
    profile = simple.CraterProfile(Input=body, SurfaceFromInput=0, SurfaceHeight=0.0)
    profile.UpdatePipeline()
    fd = fetch(profile).GetFieldData()
    value = lambda name: fd.GetArray(name).GetValue(0) if fd.GetArray(name) else float("nan")  # noqa: E731
    track = impactor_depth(state)
    num = lambda v: float("nan") if v is None else v  # noqa: E731
    print(f"t = {field_value(raw, 'Time'):.6g} s, step {int(field_value(raw, 'TimeStep'))}, "
          f"{state.GetNumberOfPoints()} particles (written to {out})")
    print(f"crater diameter {value('CraterDiameter'):.4g} m, depth {value('CraterDepth'):.4g} m, rim diameter "
          f"{value('RimDiameter'):.4g} m, rim height {value('RimHeight'):.4g} m; impactor's centre of mass "
          f"{num(track['centre_of_mass_m']):.4g} m deep, moving at {num(track['speed_m_s']):.3g} m/s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
