"""How the SPH target moves in SPHImpact checkpoints (.cksph) of the SCI stage: for each
checkpoint, the target's particles (Material 1) in four regions, with their count, mass,
vertical momentum, kinetic energy and mean vertical velocity:

    above   above the surface (z > 0.3 m: ejecta in flight and the rim's deposits near the axis)
    r<6     within 6 m of the impact point, below the surface (the crater's region)
    r6-12   6 to 12 m from it, below the surface (the target's bulk, out to its container)
    r>12    beyond 12 m (fast ejecta, most of them outside the domain)

The bulk's mean vertical velocity is what the hand-off maps onto the bed besides the crater's
own flow (docs/validation_history.md, "Depth and the SPH resolution", point 11). The checkpoint
is read by the plugin's own reader, the one ParaView opens .cksph files with.

    scripts/pvbatch benchmarks/sci_crater/target_motion.py CHECKPOINT...

The SCI checkpoints at the hand-off are the sph.cksph that `examples/sci_crater.py` writes in
its output folder.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from craterkit import fetch, field_value, load_plugin  # noqa: E402

REGIONS = ("above", "r<6", "r6-12", "r>12")


def regions_of(x):
    """The region of each particle at positions X (n x 3), as indices into REGIONS."""
    import numpy as np
    r = np.linalg.norm(x, axis=1)
    out = np.where(r < 6.0, 1, 2)
    out[x[:, 2] > 0.3] = 0
    out[r > 12.0] = 3
    return out


def target_motion(path):
    """Returns (time, {region: [count, mass, z momentum, kinetic energy]}) of the checkpoint."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    simple = load_plugin()
    try:
        data = fetch(simple.OpenDataFile(path))
    except RuntimeError as error:
        sys.exit(f"{path}: {error}")
    if data is None or data.GetNumberOfPoints() == 0 or data.GetPointData().GetArray("Material") is None:
        sys.exit(f"{path}: not a readable SPH checkpoint (see the message above)")
    pd = data.GetPointData()
    target = vtk_to_numpy(pd.GetArray("Material")) == 1
    x = vtk_to_numpy(data.GetPoints().GetData())[target]
    v = vtk_to_numpy(pd.GetArray("Velocity"))[target]
    m = vtk_to_numpy(pd.GetArray("Mass"))[target]
    where = regions_of(x)
    out = {}
    for k, name in enumerate(REGIONS):
        s = where == k
        out[name] = [int(s.sum()), float(m[s].sum()), float((m[s] * v[s, 2]).sum()),
                     float((0.5 * m[s] * (v[s] ** 2).sum(axis=1)).sum())]
    return field_value(data, "Time"), out


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    for path in argv:
        if not os.path.isfile(path):
            sys.exit(f"{path}: no such file")
        t, out = target_motion(path)
        print(f"{path} (t = {t:.1f} s)")
        print(f"  {'region':7s} {'particles':>9s} {'mass kg':>10s} {'p_z kg m/s':>11s} {'KE J':>9s} "
              f"{'mean v_z mm/s':>13s}")
        for k in REGIONS:
            c, mass, pz, ke = out[k]
            mean = 1e3 * pz / mass if mass > 0 else float("nan")
            print(f"  {k:7s} {c:9d} {mass:10.3g} {pz:11.0f} {ke:9.3g} {mean:13.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
