// When the pair lists of the bonded-particle model (Watson & Steinhauser 2017, Materials 10:379,
// seed 003; BondedSolver) must be rebuilt: a rigorous bound on the particles' RELATIVE motion
// since the build, measured region by region, so that a debris cloud whose neighbours move
// nearly together keeps its lists however fast its fastest fragments fly.
//
// The lists hold every pair closer than reach = r_eq + skin at the build; the forces need every
// pair closer than r_eq (the repulsion of Eq. 3 vanishes from r_eq on; intact bonds, Eq. 4, are
// listed however far). A pair left out was at d0 ≥ reach, and later at d ≥ d0 − |Δx_i − Δx_j|
// (Δx: the displacement since the build), so the lists hold while that difference stays within
// d0 − r_eq for every pair left out. The particles are grouped at the build into regions, cubic
// cells of L = kRegionReaches reaches (CellList's sparse layout):
//  - two particles of regions that are not neighbours were at least L apart: they are safe while
//    |Δx_i − Δx_j| ≤ L − r_eq, bounded for all particles at once by the displacements' overall
//    box (or twice the largest displacement);
//  - two of neighbouring regions R, S (or of one region) were at least the reach apart: safe while
//    |Δx_i − Δx_j| ≤ skin, bounded per pair of regions by the lesser of the norm of the per-axis
//    spans max(Hi_R − Lo_S, Hi_S − Lo_R) of the regions' displacement boxes [Lo, Hi] and m_R + m_S,
//    m the largest displacement (never more than the rule it replaces, twice Σ Δt max|v|: each
//    list lives at least as long).
// The bounds are Galilean invariant: a cloud moving as a whole triggers nothing.
// Measuring is a pass over the positions (against a copy taken at the build), so it is done only
// when it may find the lists expired: over one step two particles' displacements part by at
// most Δt min(2 max|v|, |(max v_k − min v_k)_k|) (the kick-drift's reductions, `apart`), and a
// measurement is taken when the sum of those since the last one passes the margin that one left.
#pragma once

#include "common/CellList.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

class BondedListTrigger {
public:
  // Regions' size in reaches: the far pairs' allowance L − r_eq is then ≥ 3 reaches while the
  // neighbouring regions stay small enough to move nearly together (2026-12-05, at 16 µs of the
  // headline case: 78,673 regions of ~9.5 particles).
  static constexpr double kRegionReaches = 4.0;

  // At each build: the positions (3n coordinates), r_eq and the lists' reach (r_eq + skin).
  void reset(const double* x, std::size_t n, double rEq, double reach);
  // After each drift: `apart` bounds how far this step moved any two particles relative to each
  // other. True when a pair closer than r_eq may be missing from the lists: rebuild them.
  bool expired(const double* x, double apart);
  // Measurements since construction (each a pass over the positions).
  std::size_t measurements() const { return measured_; }

private:
  // The margin left (negative: a pair may be missing), from the displacements now.
  double measure(const double* x);
  double worstNeighbourBound() const;

  CellList regions_;
  std::vector<double> built_;  // positions at the build, 3 per point
  std::vector<double> region_; // per region: Lo[3], Hi[3], m of the displacements (8 fields)
  std::vector<double> table_;  // the same per thread while they are gathered
  std::vector<std::size_t> neighbourStart_; // region c's neighbours d ≥ c: neighbour_[start[c]...]
  std::vector<std::uint32_t> neighbour_;
  std::size_t n_ = 0, measured_ = 0;
  double rEq_ = 0.0, reach_ = 0.0, far_ = 0.0; // far_: the regions' requested size L
  double margin_ = 0.0, since_ = 0.0;
};

} // namespace craterkit
