// Bodies of bonded particles for the hypervelocity model of Watson & Steinhauser 2017
// (Materials 10:379, seed 003, Section 2.1): particles on a regular cubic lattice of spacing
// r_eq = 2^{1/6} σ (every neighbour at the zero-force distance of Eqs. 3–4), masses M/N of
// their body (Eq. 20), bonds between the pairs of one body closer than r_cut at set-up (the
// assumption of Eq. 12: on the cubic lattice with r_cut = 1.5 σ these are the 6 nearest
// neighbours, the next ones being at √2 r_eq = 1.59 σ), and a small random velocity from a
// Boltzmann distribution that breaks the lattice's perfect alignment.
//
// The jitter temperature is the reduced one, k_B T / ε: with coarse-grained particles of
// ~1e-8 kg the physical k_B T would give nm/s, and the reduced temperature gives a velocity
// spread √(T ε / m) that, like the rest of the sized model, does not depend on σ.
//
// The impact: a sphere (or a cylinder along the axis) of diameter D flies along +x at v0,
// tilted by `angle` from the plate normal in the x–y plane, towards a square plate occupying
// 0 ≤ x ≤ t, |y|, |z| ≤ W/2; the projectile's path crosses the origin.
#pragma once

#include "bonded/WatsonSteinhauser2017.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct BondedBond {
  std::uint32_t i = 0, j = 0; // i < j
  double rest = 0.0;          // initial separation
};

// Particles, bonds and law of a bonded run (positions and velocities interleaved x, y, z).
struct BondedSystem {
  ws2017::Law law;
  std::vector<double> positions, velocities, masses;
  std::vector<std::uint8_t> body; // 0: projectile (or the only body), 1: plate
  std::vector<BondedBond> bonds;
  std::array<double, 3> axis{1.0, 0.0, 0.0}; // impact direction, for the debris cloud
  double rearFace = 0.0;                     // plate's rear face along the axis
  double impactSpeed = 0.0;
  std::size_t size() const { return masses.size(); }
};

enum class ProjectileShape { Sphere, Cylinder };

struct BondedImpactParams {
  double diameter = ws2017::kHeadlineDiameter; // D (m)
  ProjectileShape shape = ProjectileShape::Sphere;
  double cylinderLengthRatio = 1.0;                          // L/D of a cylinder
  double thicknessRatio = ws2017::kHeadlineThicknessRatio;   // t/D
  double plateWidthRatio = ws2017::kHeadlinePlateWidthRatio; // side of the square plate / D
  double projectileDensity = ws2017::kHeadlineDensity;       // kg/m³ (aluminium)
  double plateDensity = ws2017::kHeadlineDensity;
  double speed = 6700.0;        // v0 (m/s)
  double angle = 0.0;           // degrees from the plate normal
  double spacing = 0.0;         // lattice spacing r_eq (m); 0: from particleCount
  double particleCount = 2.0e4; // approximate total when spacing is 0
  // Law at referenceSigma (the paper's best fit at the headline size), resized to the run's σ.
  double epsilon = ws2017::kHeadlineEpsilon; // J
  double kappa = ws2017::kHeadlineKappa;     // N/m
  double rCutOverSigma = 1.5;
  double referenceSigma = 0.0; // 0: ws2017::headlineSigma()
  double temperature = 1e-3;   // k_B T / ε of the jitter
  std::uint64_t seed = 1;
  double memoryLimit = 0.0; // bytes; 0: the machine's physical memory
  void validate() const;    // throws InputError naming the property
};

// Bytes a run of n particles and about 3n bonds needs (system, solver and neighbour lists).
double estimateBondedBytes(double particles);
// Throws InputError when the estimate exceeds limit (0: physical memory) or 2^32 particles.
void checkBondedMemory(double particles, double limit, const char* property);

// The impact set-up: validate, estimate the memory, build lattice, bonds and jitter.
BondedSystem buildBondedImpact(const BondedImpactParams& params);

// A block of nx × ny × nz lattice sites at spacing a from the origin, one body of density rho
// (mass rho·(nx ny nz a³) / N), the law resized from `sizing`, bonds formed, at rest.
BondedSystem buildBondedBox(std::size_t nx, std::size_t ny, std::size_t nz, double spacing,
                            double density, const ws2017::Sizing& sizing);

// Bonds between the particles of one body closer than law.rCut, sorted by (i, j).
void formBonds(BondedSystem& system);
// Adds Maxwell–Boltzmann velocities at reduced temperature k_B T/ε to every particle, then
// removes each body's mean jitter momentum so that the bodies keep their set-up velocities.
void addBoltzmannJitter(BondedSystem& system, double temperature, std::uint64_t seed);

} // namespace craterkit
