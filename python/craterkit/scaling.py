"""Crater scaling in the gravity regime (docs/physics.md section 4.2).

Housen & Holsapple (2011, Icarus 211:856), Table 3, "sand" (cohesionless):
    R (rho/m)^(1/3) = H1 (rho/delta)^((2 + mu - 6 nu)/(3 (2 + mu))) (g a / U^2)^(-mu/(2 + mu))
with R the apparent crater radius at the pre-impact surface, m, a, delta the impactor's mass,
radius and density, rho the target's bulk density, g the gravity and U the impact speed.
"""

import math

SAND = {"mu": 0.41, "nu": 0.4, "H1": 0.59}


def impactor_radius(mass, density):
    """Radius in m of a sphere of this mass (kg) and density (kg/m^3)."""
    return (3.0 * mass / (4.0 * math.pi * density)) ** (1.0 / 3.0)


def crater_diameter(mass, speed, impactor_density, target_density, gravity, constants=SAND):
    """Apparent crater diameter 2R in m predicted by the gravity-regime pi-scaling law."""
    if min(mass, speed, impactor_density, target_density, gravity) <= 0.0:
        raise ValueError("crater_diameter: mass, speed, densities and gravity must be positive")
    mu, nu, h1 = constants["mu"], constants["nu"], constants["H1"]
    a = impactor_radius(mass, impactor_density)
    pi2 = gravity * a / speed ** 2
    ratio = target_density / impactor_density
    radius = (mass / target_density) ** (1.0 / 3.0) * h1 * ratio ** ((2 + mu - 6 * nu) / (3 * (2 + mu))) \
        * pi2 ** (-mu / (2 + mu))
    return 2.0 * radius


def formation_time(diameter, gravity):
    """Gravity-regime crater formation time scale sqrt(D / g) in s (about twice the excavation time)."""
    return math.sqrt(diameter / gravity)
