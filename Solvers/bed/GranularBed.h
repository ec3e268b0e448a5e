// GranularBed: initial particle beds for the DEM stage.
//
// HCP: a true hexagonal close-packed lattice (ABAB stacking of triangular layers, layer
// spacing 2r sqrt(2/3)); bulk packing fraction π/(3√2) = 0.7405. Box beds stand on the
// floor; bowl beds are anchored so that the top layer touches the free surface.
//
// RCP (loose, before DEM settling): radii are drawn until their volume fills the
// container to the target packing fraction, centres are placed uniformly at random, and
// overlaps are removed by collective rearrangement (Jacobi relaxation of pair overlaps
// with projection onto the container, in the spirit of Jodrey & Tory 1985 and
// Clarke & Wiley 1987) until no two spheres overlap. This reaches random loose to
// poured packings (0.50–0.60). With `settle` (the default) the loose bed is filled higher
// (its last overlaps of a few per cent left to the DEM), settled under gravity with the SSDEM
// solver and a soft, strongly damped contact law (stiffness for the fill's own weight, not an
// impact: a longer step) until its kinetic energy has decayed, unloaded by lowering gravity
// 64-fold (the contacts relax as under a 64 times stiffer law), trimmed to the surface and
// relaxed so that no two particles overlap: a dense random packing (monodisperse bulk
// 0.58–0.64, lower for higher SettlingFriction).
//
// generateGranularBed validates the parameters, runs one preparation method and measures the
// result. Each method is in a file of its own: bed/LatticeBed.h (HCP), bed/RandomFill.h (RCP
// without settling, and the loose fill for settling) and bed/SettleAndUnload.h (RCP settled).
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
  enum class Packing { RCP = 0, HCP = 1 };
  Packing packing = Packing::RCP;
  Container container;
  SizeDistribution sizes;
  double packingFraction = 0.56;   // RCP target over the whole fill volume
  double particleDensity = 2000.0; // kg/m^3 (grain density = bulk density / packing)
  int material = 0;
  std::uint64_t seed = 1;
  std::int64_t maxParticles = 2000000;
  int maxRelaxationIterations = 20000;
  bool settle = true;            // RCP: settle under gravity with the DEM
  double settlingGravity = 9.81; // m/s^2
  double settlingFriction = 0.1; // mu_s while settling (0 gives the densest packing)
  double settledEnergy = 2e-3;   // stop when E_kin < this x N m g r (mean values, kept part)

  void validate() const; // throws InputError naming the bad parameter
  static std::string packingName(Packing p) { return p == Packing::RCP ? "RCP" : "HCP"; }
};

struct GranularBedReport {
  std::size_t particles = 0;
  double bulkPackingFraction = 0.0; // measured away from walls and surface
  double topHeight = 0.0;           // highest particle top, m
  int relaxationIterations = 0;     // RCP only
  bool settled = false;             // RCP with settle: kinetic energy decayed in time
  double settlingTime = 0.0;        // s of simulated settling
  long long settlingSteps = 0;
  int finalRelaxationIterations = 0; // RCP with settle: sweeps that removed the last overlaps
  // Wall-clock seconds of each stage in the order run (RCP: "placement", "relaxation", then
  // with settle "settling", "trim", "final relaxation"); for benchmarks.
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

// Smallest gap (d - ri - rj) over all pairs, and the pair; brute force would be O(N^2),
// this uses a cell list. Returns +inf for fewer than two particles.
double smallestGap(const ParticleSet& particles, std::size_t* first = nullptr,
                   std::size_t* second = nullptr);

} // namespace craterkit
