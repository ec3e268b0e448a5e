// Cluster-pair layout of the SPH pair terms (after the cluster-pair scheme of GROMACS: Páll &
// Hess 2013, Comput. Phys. Commun. 184, 2641). The particles are sorted along a Morton curve
// and cut into clusters of kLanes consecutive ones (formed again at a list build when they
// have spread by a quarter); at each build every particle lists the clusters (with their
// periodic image code) that hold its listed neighbours (the union of its Verlet list, so the
// list's validity test covers the clusters too). Before each rate evaluation the fields the
// pair terms read are packed per cluster into one structure-of-arrays block, so a partner
// cluster's lanes are read with one contiguous vector load per field instead of one gather
// per neighbour and field. Lanes beyond the pair's support are masked in the pair loop; empty
// lanes (padding) sit far from everything.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

class NeighbourList;
struct SphState;

class ClusterList {
public:
  static constexpr std::size_t kLanes = 8; // one AVX-512 vector of doubles
  // Clusters from the state at a list build and nb's lists of that build.
  void build(const SphState& s, const NeighbourList& nb);
  std::size_t clusters() const { return member_.size() / kLanes; }
  // The particle in each lane (cluster * kLanes + lane), size() of the state for an empty lane.
  const std::vector<std::uint32_t>& member() const { return member_; }
  // Each particle's lane (cluster * kLanes + lane).
  const std::vector<std::uint32_t>& slot() const { return slot_; }
  // CSR offsets (size n + 1) and entries (cluster * 32 + periodic image code) of the clusters
  // holding each particle's listed neighbours, ascending.
  const std::vector<std::uint32_t>& start() const { return start_; }
  const std::vector<std::uint32_t>& entry() const { return entry_; }

private:
  void sortIntoClusters(const SphState& s, const NeighbourList& nb);
  double spread(const SphState& s) const;
  std::vector<std::uint32_t> member_, slot_, start_, entry_;
  std::size_t insideLanes_ = 0; // the lanes of the clusters inside the domain come first
  double formedSpread_ = 0.0;   // spread() when the clusters were formed
};

} // namespace craterkit
