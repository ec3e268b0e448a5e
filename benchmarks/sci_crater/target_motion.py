"""How the SPH target moves in SPHImpact checkpoints (.cksph) of the SCI stage: for each
checkpoint, the target's particles (Material 1) in four regions, with their count, mass,
vertical momentum, kinetic energy and mean vertical velocity:

    above   above the surface (z > 0.3 m: ejecta in flight and the rim's deposits near the axis)
    r<6     within 6 m of the impact point, below the surface (the crater's region)
    r6-12   6 to 12 m from it, below the surface (the target's bulk, out to its container)
    r>12    beyond 12 m (fast ejecta, most of them outside the domain)

The bulk's mean vertical velocity is what the hand-off maps onto the bed besides the crater's
own flow (docs/validation.md, "Depth and the SPH resolution", point 11). Stdlib only.

    python3 benchmarks/sci_crater/target_motion.py CHECKPOINT...

The SCI checkpoints at the hand-off are the sph.cksph that `examples/sci_crater.py` writes in
its output folder.
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from impactor_resolution import read_checkpoint  # noqa: E402

REGIONS = ("above", "r<6", "r6-12", "r>12")


def region(x, y, z):
    r = math.sqrt(x * x + y * y + z * z)
    if r > 12.0:
        return "r>12"
    if z > 0.3:
        return "above"
    return "r<6" if r < 6.0 else "r6-12"


def target_motion(path):
    """Returns (time, {region: [count, mass, z momentum, kinetic energy]})."""
    t, n, f = read_checkpoint(path)
    x, v, m, mat = f["x"], f["v"], f["m"], f["mat"]
    out = {k: [0, 0.0, 0.0, 0.0] for k in REGIONS}
    for i in range(n):
        if mat[i] != 1:
            continue
        a = out[region(x[3 * i], x[3 * i + 1], x[3 * i + 2])]
        vx, vy, vz = v[3 * i], v[3 * i + 1], v[3 * i + 2]
        a[0] += 1
        a[1] += m[i]
        a[2] += m[i] * vz
        a[3] += 0.5 * m[i] * (vx * vx + vy * vy + vz * vz)
    return t, out


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
