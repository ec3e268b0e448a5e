"""What the SCI impactor meets in the graded SPH target: reads SPHImpact checkpoints (.cksph) and
prints, for each, the impactor (Material 0: centre of mass, speed, smoothing length, size) and
the target particles around it (Material 1: how many lie in the pairs' support, their smoothing
length, where in the graded target they were built, their density and distention), and for the
earliest checkpoint of each coarsening the target's smoothing length down the axis below the
impact point. For every checkpoint also the cavity's floor near the axis and the target's density
in the column below it. Between consecutive checkpoints of one coarsening it splits the
impactor's sinking into what the target around it did (the target particles in its support at
the earlier checkpoint, followed by index: particles keep their order in a run and its resumes)
and its slip through that target, and prints the e-folding length of its speed. At the end, the
graded target's particle count for other coarsenings and gradings (the setup's formula).
Stdlib only (no numpy).

    python3 benchmarks/sci_crater/impactor_resolution.py [--cohesion PA] CHECKPOINT...

--cohesion: the target's cohesion of the run (ck_sph_bench's CK_COHESION; default 0), for the
pressure law of the pair forces and the count of particles at the tension cut.

The checkpoints of docs/validation.md, "Depth and the SPH resolution" (C = 10 and 8; T = 1e-3,
then windows to T = 1, 3, 10, 20 s each resumed from the last with CK_RESUME):

    CK_GRAVITY=1.5e-4 CK_CONTAINER=1 CK_LATE_STAGE="1e-3 0.46637" CK_COARSENING=C \
    CK_DOMAIN_RADIUS=29 CK_BLOCK_STEPS=7 CK_SAVE=cC_tT.cksph [CK_RESUME=cC_tPREVIOUS.cksph] \
    build/benchmarks/sph_impact/ck_sph_bench T 2 11.6

and the same straight through to T = 196 s without CK_RESUME (the hand-off). Recorded use
(2026-12-05): the checkpoints at 1 ms, 1, 3, 10, 20 s and 196 s of C = 10 and 8, one command.

Where a target particle was built is read from its mass: the graded target (sph/ImpactSetup.cpp)
gives each particle the bulk density times the volume it stands for, so (m / ρ_bulk)^(1/3) is its
spacing at build time ("build spacing" below): dx in the lattice core, growing by 1 + dx/core
per shell beyond it, up to the cap C dx. The smoothing length is κ (m/ρ)^(1/3); a pair
interacts within the mean of its two smoothing lengths (the kernel's full support).
"""

import math
import struct
import sys
from array import array

MAGIC = b"CKSPH1\n\0"
# Per-particle arrays in file order, with their components (sph/SphRun.cpp).
FIELDS = [("x", 3), ("v", 3), ("m", 1), ("rho", 1), ("u", 1), ("h", 1), ("S", 6), ("alpha", 1),
          ("D", 1)]


def read_checkpoint(path):
    """Returns (time, particle count, {field: array}) of an SPH checkpoint."""
    with open(path, "rb") as f:
        b = f.read()
    if b[:8] != MAGIC:
        sys.exit(f"{path}: not an SPH checkpoint")
    n, _steps = struct.unpack_from("<QQ", b, 8)
    t, _next_step = struct.unpack_from("<dd", b, 24)
    o, out = 40, {}
    for name, k in FIELDS:
        a = array("d")
        a.frombytes(b[o:o + 8 * n * k])
        out[name], o = a, o + 8 * n * k
    mat = array("i")
    mat.frombytes(b[o:o + 4 * n])
    out["mat"] = mat
    return t, n, out


# The late stage of the SCI run (sph/Eos.cpp, sph/Material.cpp): each material's law becomes
# p = K (rho/rho0 - 1), K = rho0 c^2, at c = 0.46637 m/s; the shear modulus keeps its ratio to
# K, so the signal speed is c sqrt(1 + 4G/(3K) rho0/rho). The solver's defaults (SphParams.h):
# cubic spline of support h, artificial viscosity alpha 1, beta 2.
C_LATE = 0.46637
GRAVITY = 1.5e-4  # m/s^2, Ryugu (CK_GRAVITY)
AV_ALPHA, AV_BETA = 1.0, 2.0
# rho0 (matrix), G/K before the switch, Drucker-Prager (pressure cut at the cone's apex) or not,
# for Materials 0 (copper.cfg) and 1, 2 (regolith.cfg).
MATERIALS = {0: (8900.0, 46e9 / 140e9, False), 1: (2700.0, 2e7 / 26.7e9, True),
             2: (2700.0, 2e7 / 26.7e9, True)}
FRICTION_ANGLE = 30.0  # degrees (ck_sph_bench's target)
COHESION = 0.0  # Pa (--cohesion)


def tension_cut():
    """The Drucker-Prager apex of sph/Strength.cpp, -k / (3B) = -c / tan(phi) (0 without cohesion;
    the regolith has no Grady-Kipp flaws, so its damage stays 0)."""
    return -COHESION / math.tan(math.radians(FRICTION_ANGLE))


def late_eos_pressure(mat, rho, alpha):
    rho0 = MATERIALS[mat][0]
    return rho0 * C_LATE ** 2 * (alpha * rho / rho0 - 1.0) / alpha


def late_pressure_and_signal(mat, rho, alpha, damage):
    rho0, g_over_k, drucker_prager = MATERIALS[mat]
    K = rho0 * C_LATE ** 2
    p = late_eos_pressure(mat, rho, alpha)
    p = max(p, tension_cut()) if drucker_prager else (p * (1.0 - damage) if p < 0.0 else p)
    return p, C_LATE * math.sqrt(1.0 + 4.0 / 3.0 * g_over_k * K / (rho * C_LATE ** 2))


def cubic_grad_over_r(r, h):
    """dW/dr / r of the cubic spline with support h (sph/Kernels.h)."""
    q, s = r / h, 8.0 / (math.pi * h ** 5)
    if q < 0.5:
        return s * (18.0 * q - 12.0)
    return -s * 6.0 * (1.0 - q) ** 2 / q if q < 1.0 else 0.0


def median(v):
    v = sorted(v)
    return v[len(v) // 2] if v else float("nan")


def sqrt_j2(S, i):
    s = S[6 * i:6 * i + 6]
    return math.sqrt(0.5 * (s[0] ** 2 + s[1] ** 2 + s[2] ** 2) + s[3] ** 2 + s[4] ** 2 + s[5] ** 2)


class Checkpoint:
    def __init__(self, path):
        self.path = path.split("/")[-1]
        self.t, n, s = read_checkpoint(path)
        self.s = s
        x, m, mat = s["x"], s["m"], s["mat"]
        self.imp = [i for i in range(n) if mat[i] == 0]
        self.tgt = [i for i in range(n) if mat[i] == 1]
        M = sum(m[i] for i in self.imp)
        self.M = M
        self.com = [sum(m[i] * x[3 * i + k] for i in self.imp) / M for k in range(3)]
        self.vcom = [sum(m[i] * s["v"][3 * i + k] for i in self.imp) / M for k in range(3)]
        # The undisturbed target's bulk density: far from the impact (beyond 5 m, above 20 m).
        far = [s["rho"][i] for i in self.tgt
               if 5.0 < math.dist((x[3 * i], x[3 * i + 1], x[3 * i + 2]), (0, 0, 0)) < 20.0]
        self.rho_bulk = median(far)
        self.label = {i: (m[i] / self.rho_bulk) ** (1.0 / 3.0) for i in self.tgt}
        self.dx = min(self.label.values())  # the lattice core's spacing
        self.coarsening = max(self.label.values()) / self.dx

    def pos(self, i):
        x = self.s["x"]
        return (x[3 * i], x[3 * i + 1], x[3 * i + 2])

    def impactor(self):
        s, imp = self.s, self.imp
        pts = [self.pos(i) for i in imp]
        size = max(math.dist(p, q) for p in pts for q in pts)
        ke = sum(0.5 * s["m"][i] * sum(s["v"][3 * i + k] ** 2 for k in range(3)) for i in imp)
        return {"depth": -self.com[2], "r_axis": math.hypot(self.com[0], self.com[1]),
                "speed": math.sqrt(sum(c * c for c in self.vcom)), "vz": self.vcom[2],
                "h": sum(s["h"][i] for i in imp) / len(imp), "size": size, "ke": ke,
                "rho": median(s["rho"][i] for i in imp)}

    def graded_spacing(self, r):
        """The build spacing of the graded target at radius r (sph/ImpactSetup.cpp)."""
        core = 4.0 * self.dx  # four impactor radii: 4 dx at two particles across (dx = radius)
        return min(self.coarsening * self.dx, self.dx * max(1.0, r / core))

    def surroundings(self):
        """Target particles in the pair support of any impactor particle, and near its centre."""
        s, h = self.s, self.s["h"]
        imp_pos = [(self.pos(i), h[i]) for i in self.imp]
        hi = sum(hh for _, hh in imp_pos) / len(imp_pos)
        inside, within2h, core_near = [], 0, 0
        own = {i: [] for i in self.imp}  # each impactor particle's own target neighbours
        for j in self.tgt:
            p = self.pos(j)
            dc = math.dist(p, self.com)
            if dc < 2.0 * hi:
                within2h += 1
            if dc < 0.5 and self.label[j] < 1.5 * self.dx:
                core_near += 1
            near = [i for i, (q, hq) in zip(self.imp, imp_pos) if math.dist(p, q) < 0.5 * (hq + h[j])]
            for i in near:
                own[i].append(j)
            if near:
                inside.append(j)
        mass = sum(s["m"][j] for j in inside)
        # The target's mass-weighted velocity in the impactor's support: is it carried along?
        vt = [sum(s["m"][j] * s["v"][3 * j + k] for j in inside) / mass for k in range(3)] \
            if inside else [float("nan")] * 3
        return {"v_target": vt, "inside": inside, "own": own,
                "n": len(inside), "within2h": within2h, "core_near": core_near,
                "h": median(h[j] for j in inside), "label": median(self.label[j] for j in inside),
                "mass_ratio": mass / self.M,
                "rho_rel": median(s["rho"][j] / self.rho_bulk for j in inside),
                "alpha": median(s["alpha"][j] for j in inside),
                "j2": median(sqrt_j2(s["S"], j) for j in inside)}

    def impactor_forces(self):
        """The pair forces on the impactor's particles from all others (sph/SphSolver.cpp's pair
        terms, with the late stage's pressure and signal speed): the total of each term along the
        impactor's motion (N, positive = decelerating), and per particle the ratio of its
        quadratic-viscosity deceleration to v^2 (1/m) with its neighbours' mean pair support."""
        s = self.s
        x, v, m, rho, h, S = s["x"], s["v"], s["m"], s["rho"], s["h"], s["S"]
        n = len(m)
        pr, cs = {}, {}

        def state(j):
            if j not in pr:
                p, c = late_pressure_and_signal(s["mat"][j], rho[j], s["alpha"][j], s["D"][j])
                pr[j], cs[j] = p / rho[j] ** 2, c
            return pr[j], cs[j]

        speed = math.sqrt(sum(c * c for c in self.vcom))
        back = [-c / speed for c in self.vcom]  # unit vector against the motion
        tot = {"pressure": 0.0, "visc_linear": 0.0, "visc_quadratic": 0.0, "stress": 0.0}
        per = []
        for a in self.imp:
            pa, ca = state(a)
            xa, va = x[3 * a:3 * a + 3], v[3 * a:3 * a + 3]
            sa = [S[6 * a + k] / rho[a] ** 2 for k in range(6)]
            va2 = sum(c * c for c in va)
            quad_along_v, hbs = 0.0, []
            for b in range(n):
                if b == a:
                    continue
                rx, ry, rz = xa[0] - x[3 * b], xa[1] - x[3 * b + 1], xa[2] - x[3 * b + 2]
                hb = 0.5 * (h[a] + h[b])
                r2 = rx * rx + ry * ry + rz * rz
                if r2 >= hb * hb or r2 == 0.0:
                    continue
                pb, cb = state(b)
                g = cubic_grad_over_r(math.sqrt(r2), hb)
                vx, vy, vz = va[0] - v[3 * b], va[1] - v[3 * b + 1], va[2] - v[3 * b + 2]
                vr = vx * rx + vy * ry + vz * rz
                mu = hb * vr / (r2 + 0.01 * hb * hb) if vr < 0.0 else 0.0
                lin = -AV_ALPHA * (ca + cb) * mu / (rho[a] + rho[b])
                quad = 2.0 * AV_BETA * mu * mu / (rho[a] + rho[b])
                mg = m[b] * g
                sb = [S[6 * b + k] / rho[b] ** 2 for k in range(6)]
                t = [sa[k] + sb[k] for k in range(6)]
                r = (rx, ry, rz)
                acc = {"pressure": [-mg * (pa + pb) * c for c in r],
                       "visc_linear": [-mg * lin * c for c in r],
                       "visc_quadratic": [-mg * quad * c for c in r],
                       "stress": [mg * (t[0] * rx + t[3] * ry + t[4] * rz),
                                  mg * (t[3] * rx + t[1] * ry + t[5] * rz),
                                  mg * (t[4] * rx + t[5] * ry + t[2] * rz)]}
                for key, av in acc.items():
                    tot[key] += m[a] * sum(av[k] * back[k] for k in range(3))
                if va2 > 0.0:
                    quad_along_v -= sum(acc["visc_quadratic"][k] * va[k] for k in range(3)) / \
                        math.sqrt(va2)
                if s["mat"][b] != 0:
                    hbs.append(hb)
            if va2 > 0.0 and hbs:
                per.append((quad_along_v / va2, sum(hbs) / len(hbs), len(hbs)))
        return tot, per

    def floor_and_column(self):
        """The cavity's floor: the median of the 10 shallowest target particles' depths in
        annuli about the axis (0-0.5, 0.5-1, 1-2, 2-3 m); the median density over the bulk
        density within 1 m of the axis in 1 m depth bins from 0 to 8 m."""
        x, tgt = self.s["x"], self.tgt
        floor = []
        for r0, r1 in ((0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 3.0)):
            zs = sorted(-x[3 * j + 2] for j in tgt if r0 <= math.hypot(x[3 * j], x[3 * j + 1]) < r1)
            floor.append(median(zs[:10]))
        column = []
        for z0 in range(8):
            column.append(median(self.s["rho"][j] / self.rho_bulk for j in tgt
                                 if math.hypot(x[3 * j], x[3 * j + 1]) < 1.0
                                 and z0 <= -x[3 * j + 2] < z0 + 1))
        return floor, column

    def tension(self):
        """The target within 1 m of the axis, 0-8 m deep: its count, how many the late-stage law
        puts in tension and how many of them at the tension cut."""
        x, s = self.s["x"], self.s
        sel = [j for j in self.tgt
               if math.hypot(x[3 * j], x[3 * j + 1]) < 1.0 and 0.0 <= -x[3 * j + 2] < 8.0]
        p = [late_eos_pressure(1, s["rho"][j], s["alpha"][j]) for j in sel]
        return len(sel), sum(1 for q in p if q < 0.0), sum(1 for q in p if q <= tension_cut())

    def axis_profile(self, bins, radius=0.3):
        """Median smoothing length and build spacing of the target within `radius` of the axis."""
        rows = []
        for z0, z1 in bins:
            sel = [j for j in self.tgt
                   if -z1 <= self.s["x"][3 * j + 2] < -z0
                   and math.hypot(self.s["x"][3 * j], self.s["x"][3 * j + 1]) < radius]
            rows.append((z0, z1, len(sel), median(self.s["h"][j] for j in sel),
                         median(self.label[j] for j in sel)))
        return rows


def graded_count(dx, coarsening, radius, fine_cap=None, fine_radius=0.0):
    """Target particles of the graded hemisphere (sph/ImpactSetup.cpp's gradedShells and lattice
    core: shells of thickness min(C dx, dx r / core), core = 4 dx), optionally with the spacing
    held at most fine_cap * dx out to fine_radius (a grading the code does not offer)."""
    core = 4.0 * dx
    mc = math.ceil(core / dx)
    n = sum(1 for k in range(mc) for j in range(-mc, mc) for i in range(-mc, mc)
            if ((i + 0.5) ** 2 + (j + 0.5) ** 2 + (k + 0.5) ** 2) * dx * dx <= core * core)
    r = core
    while r < radius:
        t = min(coarsening * dx, dx * max(1.0, r / core))
        if fine_cap is not None and r < fine_radius:
            t = min(t, fine_cap * dx)
        elif fine_cap is not None:  # beyond: grow again by dx/core per shell from the fine cap
            t = min(coarsening * dx, max(fine_cap * dx, t_prev * (1.0 + dx / core)))
        mid = r + 0.5 * t
        n += max(1, round(2.0 * math.pi * mid * mid / (t * t)))
        r, t_prev = r + t, t
    return n


def main(paths):
    global COHESION
    if paths[:1] == ["--cohesion"] and len(paths) > 1:
        COHESION = float(paths[1])
        if not COHESION >= 0.0 or not math.isfinite(COHESION):
            sys.exit("--cohesion must be a finite cohesion in Pa, 0 or more")
        paths = paths[2:]
    if not paths or paths[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if paths else 2
    cps = sorted((Checkpoint(p) for p in paths), key=lambda c: (-round(c.coarsening), c.t))
    first = {}
    for c in cps:
        first.setdefault(round(c.coarsening), c)
    for C, c in first.items():
        kappa = median(c.s["h"][j] / (c.s["m"][j] / c.s["rho"][j]) ** (1 / 3) for j in c.tgt)
        imp = c.impactor()
        print(f"== coarsening {C} ({c.path}, t = {c.t:.4g} s): dx {c.dx:.4f} m, cap {C * c.dx:.3f} m "
              f"from r = {C * 4 * c.dx:.2f} m, target bulk density {c.rho_bulk:.1f} kg/m3, "
              f"kappa {kappa:.2f}, impactor h {imp['h']:.4f} m")
        print("   target within 0.3 m of the axis: depth (m) | particles | median h (m) | "
              "build spacing (m) | h / impactor h")
        bins = [(0.0, 0.25), (0.25, 0.5), (0.5, 0.75), (0.75, 1.0), (1.0, 1.5), (1.5, 2.0),
                (2.0, 2.5), (2.5, 3.0), (3.0, 4.0), (4.0, 5.0)]
        for z0, z1, n, hm, lm in c.axis_profile(bins):
            print(f"   {z0:4.2f}-{z1:4.2f} | {n:5d} | {hm:.3f} | {lm:.3f} | {hm / imp['h']:.1f}")
    print("== per checkpoint: t (s), C | impactor depth, speed, KE, h, size (m) | graded spacing "
          "at its radius | target in its support: count, median h, build spacing, mass / "
          "impactor's, rho/rho_bulk, alpha, sqrt(J2) (Pa) | within 2 h_imp | core-built within 0.5 m")
    prev = {}
    for c in cps:
        C = round(c.coarsening)
        imp, sur = c.impactor(), c.surroundings()
        r = math.dist(c.com, (0.0, 0.0, 0.0))
        print(f"t {c.t:<6.4g} C {C:2d} | depth {imp['depth']:.3f} (axis offset {imp['r_axis']:.3f}), "
              f"speed {imp['speed']:.3g} m/s, KE {imp['ke']:.3g} J, h {imp['h']:.4f}, size "
              f"{imp['size']:.3f} | graded {c.graded_spacing(r):.3f} | support {sur['n']:3d}, h "
              f"{sur['h']:.3f} ({sur['h'] / imp['h']:.1f} x impactor's), built at {sur['label']:.3f}, "
              f"mass {sur['mass_ratio']:.1f} x, rho {sur['rho_rel']:.3f}, alpha {sur['alpha']:.3f}, "
              f"sqrtJ2 {sur['j2']:.3g} | 2h {sur['within2h']} | core {sur['core_near']}")
        if C in prev:
            p = prev[C]
            dz = imp["depth"] - p["depth"]
            # Particles keep their order in a run and its resumes: follow the target that was in
            # the impactor's support at the earlier checkpoint (mass-weighted mean depth).
            m, x = c.s["m"], c.s["x"]
            was = p["inside"]
            carried = -sum(m[j] * (x[3 * j + 2] - p["z"][j]) for j in was) / sum(m[j] for j in was)
            print(f"     window from t {p['t']:.4g} s: the target then in its support sank "
                  f"{carried:.3f} m, the impactor {dz:.3f} m: slip through the target "
                  f"{dz - carried:.3f} m")
            slips = []
            for i, was_i in p["own"].items():
                if was_i:
                    ci = -sum(m[j] * (x[3 * j + 2] - p["z"][j]) for j in was_i) / \
                        sum(m[j] for j in was_i)
                    slips.append(-(x[3 * i + 2] - p["zi"][i]) - ci)
            slips.sort()
            print(f"     each particle's slip past its own neighbours (m): median "
                  f"{median(slips):.3f}; " + " ".join(f"{v:.2f}" for v in slips))
            if imp["speed"] > 0 and p["speed"] > imp["speed"] and dz > 0:
                L = dz / math.log(p["speed"] / imp["speed"])
                print(f"     window from t {p['t']:.4g} s: sank {dz:.3f} m, speed {p['speed']:.3g} -> "
                      f"{imp['speed']:.3g} m/s: e-folding length {L:.3f} m; mean support h "
                      f"{0.5 * (p['hsup'] + sur['h']):.3f} m (ratio L/h "
                      f"{L / (0.5 * (p['hsup'] + sur['h'])):.2f})")
            else:
                print(f"     window from t {p['t']:.4g} s: sank {dz:.3f} m, speed {p['speed']:.3g} -> "
                      f"{imp['speed']:.3g} m/s")
        depths = sorted(-c.s["x"][3 * i + 2] for i in c.imp)
        print(f"     its particles' depths (m), median {median(depths):.3f} (of the 8: the deeper of the "
              f"middle two): " + " ".join(f"{d:.2f}" for d in depths))
        floor, column = c.floor_and_column()
        print("     floor (median of the 10 shallowest target depths, m) at 0-0.5/0.5-1/1-2/2-3 m "
              "from the axis: " + " ".join(f"{d:.2f}" for d in floor) +
              "; target density / bulk within 1 m of the axis, depth 0-1 ... 7-8 m: " +
              " ".join(f"{d:.2f}" for d in column))
        if c.t > 1.001e-3:  # the late-stage law
            n, below, cut = c.tension()
            print(f"     target within 1 m of the axis, 0-8 m deep: {n} particles, {below} in tension "
                  f"by the law, {cut} at the tension cut {tension_cut() + 0.0:.3g} Pa")
        vt = sur["v_target"]
        rel = math.sqrt(sum((c.vcom[k] - vt[k]) ** 2 for k in range(3)))
        print(f"     target in the support moves at vz {vt[2]:.3g} m/s (impactor {c.vcom[2]:.3g}); "
              f"relative speed {rel:.3g} m/s")
        if c.t <= 1.001e-3:  # before the switch: the early-stage laws hold, not these
            prev[C] = dict(imp, t=c.t, hsup=sur["h"], inside=sur["inside"], own=sur["own"],
                           z={j: c.s["x"][3 * j + 2] for j in sur["inside"]},
                           zi={i: c.s["x"][3 * i + 2] for i in c.imp})
            continue
        tot, per = c.impactor_forces()
        mv2 = c.M * imp["speed"] ** 2
        total = sum(tot.values())
        length = f"{mv2 / total:.3g} m" if total > 0.0 else "- (no net drag)"
        print("     forces along the motion (N, + decelerates): " +
              ", ".join(f"{k} {v:.3g}" for k, v in tot.items()) +
              f"; weight {c.M * GRAVITY:.3g}; M v^2 {mv2:.3g} J: drag length M v^2 / (sum) {length}")
        if per:
            k = median(p[0] for p in per)
            print(f"     per particle: quadratic-viscosity deceleration / v^2 median {k:.3g} 1/m "
                  f"(length {1 / k:.3g} m); mean pair support {median(p[1] for p in per):.3f} m; "
                  f"neighbours {median(p[2] for p in per)}; length x support "
                  f"{1 / k / median(p[1] for p in per):.2f}")
        prev[C] = dict(imp, t=c.t, hsup=sur["h"], inside=sur["inside"], own=sur["own"],
                           z={j: c.s["x"][3 * j + 2] for j in sur["inside"]},
                           zi={i: c.s["x"][3 * i + 2] for i in c.imp})
    dx = cps[0].dx
    print(f"== target particles of the graded hemisphere (radius 11.6 m, dx {dx:.4f} m; the "
          f"container's shells not counted)")
    for C in (15, 10, 8, 7, 5, 4, 2):
        print(f"   coarsening {C:2d}: {graded_count(dx, C, 11.6)}")
    for fine, rf in ((2, 5.0), (3, 5.0), (2, 3.0)):
        print(f"   spacing at most {fine} dx to {rf} m, then graded to 10 dx: "
              f"{graded_count(dx, 10, 11.6, fine, rf)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
