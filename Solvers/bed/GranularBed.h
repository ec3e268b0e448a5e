// GranularBed: initial particle beds for the DEM stage.
//
// HCP: a true hexagonal close-packed lattice (ABAB stacking of triangular layers, layer
// spacing 2r sqrt(2/3)); bulk packing fraction π/(3√2) = 0.7405. Box beds stand on the
// floor; bowl beds are anchored so that the top layer touches the free surface.
//
// RCP without settling: radii are drawn until their volume fills the container to the target
// packing fraction, centres are placed uniformly at random, and overlaps are removed by
// collective rearrangement (Jacobi relaxation of pair overlaps with projection onto the
// container, in the spirit of Jodrey & Tory 1985 and Clarke & Wiley 1987) until no two spheres
// overlap: random loose to poured packings (0.50–0.60), not at rest under gravity.
//
// RCP with `settle` (the default) and Loose: the loose fill is filled higher (its last overlaps
// of a few per cent left to the DEM), poured and settled under gravity with the SSDEM solver and
// a soft, strongly damped contact law (stiffness for the fill's own weight, not an impact: a
// longer step) until its kinetic energy has decayed, unloaded to a quarter of its weight, its
// contacts stiffened to the DEM stage's law at most fourfold at a time (gravity lowered by the
// same factor before each step, so that the contact forces carry over), trimmed to the surface,
// and brought to rest under full gravity in the DEM stage's own contact law (its default
// coefficients, k_N and step as DEMIntegrator chooses them from the stage* fields): the overlaps
// carry the bed's weight, so the DEM stage starts from rest (but for the contact history, which
// the bed does not carry: the stage's springs start from zero). RCP settles with low friction
// (SettlingFriction): a dense random packing (monodisperse bulk 0.58–0.64). Loose pours with
// high sliding and rolling friction, the DEM stage's defaults (0.6, 0.35; twisting 0.4375: a 30
// degree angle of repose), and no compaction: a loose random packing (monodisperse bulk about
// 0.57–0.58), as loose as regolith.
//
// generateGranularBed validates the parameters, runs one preparation method and measures the
// result. Each method is in a file of its own: bed/LatticeBed.h (HCP), bed/RandomFill.h (RCP
// without settling, and the loose fill for settling) and bed/SettleAndUnload.h (RCP settled,
// Loose).
#pragma once

#include "bed/SizeDistribution.h"
#include "common/Container.h"
#include "common/ParticleSet.h"
#include "common/Progress.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace craterkit {

struct GranularBedParams {
  enum class Packing { RCP = 0, HCP = 1, Loose = 2 };
  Packing packing = Packing::RCP;
  Container container;
  SizeDistribution sizes;
  double packingFraction = 0.56;   // RCP target over the whole fill volume
  double particleDensity = 2000.0; // kg/m^3 (grain density = bulk density / packing)
  int material = 0;
  std::uint64_t seed = 1;
  std::int64_t maxParticles = 2000000;
  int maxRelaxationIterations = 20000;
  bool settle = true;            // RCP: settle under gravity with the DEM (Loose always does)
  double settlingGravity = 9.81; // m/s^2
  double settlingFriction = 0.1; // RCP: mu_s while settling (0 gives the densest packing)
  double settledEnergy = 2e-3;   // stop when E_kin < this x N m g r (mean values, kept part)
  // The DEM stage the settled bed is handed to (DEMIntegrator's MaxExpectedSpeed, MaxOverlap
  // and NormalStiffness, with its default contact law and 30 steps per collision): the bed ends
  // at rest in that law under settlingGravity.
  double stageMaxExpectedSpeed = 1.0; // m/s
  double stageMaxOverlap = 0.01;      // of the smallest radius
  double stageNormalStiffness = 0.0;  // N/m; <= 0: chosen as DEMIntegrator chooses it

  void validate() const; // throws InputError naming the bad parameter
  // Whether the preparation settles the bed under gravity (and ends at rest in the stage's law).
  bool settles() const { return packing == Packing::Loose || (packing == Packing::RCP && settle); }
  static std::string packingName(Packing p) {
    return p == Packing::RCP ? "RCP" : p == Packing::HCP ? "HCP" : "Loose";
  }
};

struct GranularBedReport {
  std::size_t particles = 0;
  double bulkPackingFraction = 0.0; // measured away from walls and surface
  double topHeight = 0.0;           // highest particle top, m
  int relaxationIterations = 0;     // RCP only
  bool settled = false;             // RCP with settle: kinetic energy decayed in time
  double settlingTime = 0.0;        // s of simulated settling
  long long settlingSteps = 0;
  double coordinationNumber = 0.0; // mean touching neighbours, away from walls and surface
  // A settled bed's rest in the DEM stage's law: its k_N (N/m) and step (s), the simulated time
  // and steps, whether the fastest grain fell below the rest speed, and that speed at the end
  // (in units of sqrt(g r), r the mean radius).
  double stageStiffness = 0.0;
  double stageTimeStep = 0.0;
  double restTime = 0.0;
  long long restSteps = 0;
  bool atRest = false;
  double restSpeed = 0.0;
  // Wall-clock seconds of each stage in the order run (RCP: "placement", "relaxation", then
  // with settle, and Loose, "settling", "stiffening", "trim", "rest"); for benchmarks.
  std::vector<std::pair<std::string, double>> stageSeconds;
};

// Builds the bed. Throws InputError on bad parameters, Aborted if progress says stop.
ParticleSet generateGranularBed(const GranularBedParams& params,
                                GranularBedReport* report = nullptr,
                                const ProgressCallback& progress = {});

// Volume fraction occupied by spheres inside the container region at least `margin` from
// its walls and surface, estimated with `samples` low-discrepancy points (Kronecker
// sequence) tested against the spheres with a cell list. Error ~ 1/samples.
double measurePackingFraction(const ParticleSet& particles, const Container& container,
                              double margin, std::size_t samples = 1000000);

// Mean number of grains each grain touches (centre distance at most the sum of the radii, to
// 1e-9 of it), over the grains whose centre lies at least `margin` inside the container: the
// coordination number of the bulk (rattlers included). NaN if no grain is that far inside.
double coordinationNumber(const ParticleSet& particles, const Container& container, double margin);

// Smallest gap (d - ri - rj) over all pairs, and the pair; brute force would be O(N^2),
// this uses a cell list. Returns +inf for fewer than two particles.
double smallestGap(const ParticleSet& particles, std::size_t* first = nullptr,
                   std::size_t* second = nullptr);

} // namespace craterkit
