// The SPH pair terms computed once per pair, over clusters of eight particles (the cluster-pair
// scheme of GROMACS's short-range kernels, for SphSolver.cpp's pairSums): the particles are
// sorted into slabs along the longest axis and, within a slab, along a Morton curve, and cut
// into clusters of eight whose fields are packed one row of eight lanes per field. A cluster
// lists the clusters at or after it that hold its particles' support-list entries
// (sph/SupportList.h); the kernel takes each particle of cluster I in turn against the eight
// lanes of a listed cluster J, lanes outside the support masked, and adds each pair's terms to
// both: I's side into its particle's vector sums, J's side into J's eight lanes, summed in
// registers over I's eight particles before they reach memory. No support pass, and half the
// pair terms of the two-sided loop (benchmarks/JOURNAL.md, "Each pair once").
//
// Deterministic for any thread count: a slab is at least the longest listing reach wide, so
// a cluster's partners lie in its own slab or the next; the even slabs run first (in parallel,
// none touching another's clusters), then the odd ones, each slab's clusters in order by one
// thread. The sums therefore add up in one fixed order, though not in the two-sided loop's:
// the rates differ from it by rounding.
#pragma once

#include "sph/PairTerms.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

class SupportList;

// A cluster's fields, one row of eight lanes each.
enum ClusterField : int {
  kCx,
  kCy,
  kCz,
  kCh,
  kCvx,
  kCvy,
  kCvz,
  kCrho,
  kCm,
  kCvol,
  kCpr,
  kCc,
  kCs0,
  kClusterFields = kCs0 + 6
};
struct alignas(64) ClusterBlock {
  double f[kClusterFields][8];
};
// A cluster's sums, one row of eight lanes each, in PairSums' order: acc (3), dr, de, grad
// (9), xs (3), sig.
constexpr int kClusterSums = 18;
struct alignas(64) ClusterSums {
  double a[kClusterSums][8];
};

// The pair terms of clusters [first, last) against their listed partners (CSR: start,
// partner), each pair once, added to `sums` (sig: the largest). Where wideKernelAvailable().
// K: the kernel (sph/Kernels.h); Xsph: with the XSPH term. The velocity gradient is summed for
// every particle (the caller uses it for solids only).
template <class K, bool Xsph>
void clusterPairSums(const ClusterBlock* blocks, const std::uint32_t* start,
                     const std::uint32_t* partner, std::uint32_t first, std::uint32_t last,
                     ClusterSums* sums, const PairConstants& pc);

class ClusterPairs {
public:
  // Forms the clusters and their list at positions X from the support list's entries (no
  // periodic images), unless already formed for this draw of it. Returns whether the clusters
  // can be used: false where there are fewer than four slabs (a body not four reaches long).
  bool follow(const PairPosition* X, std::size_t n, const SupportList& list);
  // Every particle's pair sums from its record P and position X.
  template <class K, bool Xsph>
  void evaluate(const PairRecord* P, const PairPosition* X, const PairConstants& pc);
  const PairSums& of(std::size_t a) const { return out_[a]; }

private:
  void form(const PairPosition* X, std::size_t n, const SupportList& list);
  void pack(const PairRecord* P, const PairPosition* X);

  std::vector<std::uint32_t> slot_;      // each particle's cluster * 8 + lane
  std::vector<std::int64_t> member_;     // each slot's particle, or -1 (padding)
  std::vector<std::uint32_t> slabStart_; // first cluster of each slab, and the end
  std::vector<std::uint32_t> start_, partner_;
  std::vector<std::uint32_t> phase_[2]; // the even slabs, then the odd ones
  std::vector<PairSums> out_;           // each particle's sums
  std::vector<ClusterBlock> block_;
  std::vector<ClusterSums> sums_;
  std::size_t draw_ = 0; // the support list's draw the clusters follow
  bool formed_ = false, usable_ = false;
};

} // namespace craterkit
