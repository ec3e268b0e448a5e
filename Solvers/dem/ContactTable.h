// The DEM's compact contact tables (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012): the
// pairs in contact, and the (particle, wall) pairs within reach, with their contact histories
// (ContactHistory: tangential spring, rolling displacement, twisting angle, last normal).
//
// A bed at rest has a few per cent of its listed pairs in contact. The pair list
// (dem/PairList.h) keeps per pair only its particles, a flag and a row of the table; the table
// holds the contacts' histories as arrays of components. Each step writes a new
// table from the pairs found touching, in the order of the pair list; each row reads its
// history from its row of the previous table (`from`; the zero row past the end for a new
// contact), so the contact law runs over contiguous arrays. The results (forces and torques,
// kResultWords a row) are read in the step that writes them, so the two tables share one
// array of them (ContactResults), kept by the solver. The loop is written for SIMD
// (`omp simd`, a branch-free law, compiled for AVX-512 and generic x86-64 as in
// common/SimdClones.h): GCC 12 runs the AVX-512 version eight contacts at once (the body is one
// inlined call, so that its local arrays do not become per-lane arrays) and keeps the generic
// one scalar (-fopt-info-vec: "control flow in loop"). The lanes do the scalar law's operations
// in its order, without fused multiply-adds: both versions give the same bits. Every contact is
// evaluated on its own: the results depend neither on its row nor on the number of threads.
#pragma once

#include "common/GrowFresh.h"
#include "dem/ContactModels.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct ContactTable {
  static constexpr int kHistoryWords = 10; // spring (3), rolling (3), twisting, normal (3)
  static constexpr int kResultWords = 9;   // force on first, torque on first, on second (results)

  std::size_t rows = 0;
  // FreshVector: the rows a growth adds are left unwritten, and the threads that fill them touch
  // their pages first (common/GrowFresh.h).
  FreshVector<std::uint32_t> first, second; // the particles, first < second
  FreshVector<std::uint32_t> from;          // row in the previous table (its `rows`: new)
  // Component q of row c's history is history[q][c]; row `rows` is all zero (a new contact).
  std::array<FreshVector<double>, kHistoryWords> history;

  // Sets the number of rows (keeping the memory; rows it adds are zero) and zeroes the history
  // row past the end.
  void resize(std::size_t count);
  // Room for `count` rows and the zero row (serially, before the fill), so that setRows up to it
  // allocates nothing. For a table about to be
  // filled: a growth neither keeps nor zeroes the rows (their pages stay untouched until the
  // fill writes them), so room for every listed pair costs address space only.
  void reserveRows(std::size_t count);
  // Sets the number of rows (at most the reserved count) and zeroes the history row past the end.
  void setRows(std::size_t count);
  ContactHistory historyAt(std::size_t row) const;
  void setHistory(std::size_t row, const ContactHistory& h);
  // Drops the rows of removed particles and renumbers the rest (newIndex is increasing, so
  // the order stays); newRow receives each old row's new row.
  void removeParticles(const std::vector<char>& remove, const std::vector<std::uint32_t>& newIndex,
                       std::vector<std::uint32_t>& newRow);
};

// Particle data the contact law reads: positions, radii, masses, predicted velocities, spins.
struct ContactInputs {
  const double *x, *r, *m, *v, *w;
};

// Evaluates rows [begin, end) of NOW: the geometry from the particles, the history from
// BEFORE's row now.from[c], the contact law (ssdemContactLane); writes each row's history, and
// its result to kResultWords words of RESULT from kResultWords * c. Returns the largest overlap
// relative to the smaller radius (0 if none).
double evaluateContacts(const LinearSpringDashpot& law, const FrictionConstants& fc, double dt,
                        const ContactInputs& in, const ContactTable& before, ContactTable& now,
                        double* result, std::size_t begin, std::size_t end);
double evaluateContacts(const Hertz& law, const FrictionConstants& fc, double dt,
                        const ContactInputs& in, const ContactTable& before, ContactTable& now,
                        double* result, std::size_t begin, std::size_t end);

// The (particle, wall) pairs within reach at the last neighbour-list build, sorted by particle
// then wall, with their histories stored densely (only the grains at the container touch it).
// Carried across rebuilds by merging each particle's old and new entries, on all threads.
struct WallContacts {
  std::vector<std::size_t> start; // n + 1: entries start[i] .. start[i+1]-1 are particle i's
  std::vector<std::uint32_t> particle, wall;
  std::vector<ContactHistory> history;
  std::vector<char> active; // in contact at the last force evaluation

  std::size_t size() const { return particle.size(); }
  // Rebuilds from per-particle masks of the walls within reach (bit w: wall w), keeping the
  // history and flag of every entry that stays.
  void build(const std::vector<std::uint64_t>& near);
  // Drops the entries of removed particles and renumbers the rest; needs a build() after.
  void removeParticles(const std::vector<char>& remove, const std::vector<std::uint32_t>& newIndex);

private:
  // The previous build's arrays, reused by the next one (no fresh pages at every rebuild).
  std::vector<std::size_t> spareStart_;
  std::vector<std::uint32_t> spareParticle_, spareWall_;
  std::vector<ContactHistory> spareHistory_;
  std::vector<char> spareActive_;
};

} // namespace craterkit
