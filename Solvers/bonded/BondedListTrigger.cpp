#include "bonded/BondedListTrigger.h"

#include "common/OpenMP.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace craterkit {
namespace {

// Per region: Lo[3] and Hi[3] of the displacements' box and m, the largest displacement (its
// square while it is gathered); eight fields, one cache line.
constexpr std::size_t kFields = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEmpty[kFields] = {kInf, kInf, kInf, -kInf, -kInf, -kInf, 0.0, 0.0};

double norm3(double a, double b, double c) { return std::sqrt(a * a + b * b + c * c); }

} // namespace

void BondedListTrigger::reset(const double* x, std::size_t n, double rEq, double reach) {
  n_ = n, rEq_ = rEq, reach_ = reach, far_ = kRegionReaches * reach;
  regions_.buildSparse(x, n, far_);
  built_.assign(x, x + 3 * n);
  // Each region's neighbours from its own number on (each pair once), listed once per build: the
  // cell list's rows name them through two dependent look-ups a row.
  const long cells = static_cast<long>(regions_.occupiedCells());
  neighbourStart_.assign(static_cast<std::size_t>(cells) + 1, 0);
  auto forEachLater = [&](std::size_t c, auto&& visit) {
    regions_.forEachNeighbourCellRange(c, [&](std::size_t first, std::size_t last) {
      for (std::size_t d = std::max(first, c); d < last; ++d)
        visit(d);
    });
  };
#pragma omp parallel for schedule(static)
  for (long c = 0; c < cells; ++c) {
    std::uint32_t count = 0;
    forEachLater(static_cast<std::size_t>(c), [&](std::size_t) { ++count; });
    neighbourStart_[static_cast<std::size_t>(c) + 1] = count;
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(cells); ++c)
    neighbourStart_[c + 1] += neighbourStart_[c];
  neighbour_.resize(neighbourStart_.back());
#pragma omp parallel for schedule(static)
  for (long c = 0; c < cells; ++c) {
    std::uint32_t* out = neighbour_.data() + neighbourStart_[static_cast<std::size_t>(c)];
    forEachLater(static_cast<std::size_t>(c),
                 [&](std::size_t d) { *out++ = static_cast<std::uint32_t>(d); });
  }
  margin_ = reach - rEq; // nothing has moved: every pair left out is the skin or more from r_eq
  since_ = 0.0;
}

bool BondedListTrigger::expired(const double* x, double apart) {
  since_ += apart;
  if (since_ <= margin_)
    return false;
  margin_ = measure(x);
  since_ = 0.0;
  return margin_ < 0.0;
}

// Each region's displacement box and largest displacement, from one pass over the particles in
// index order (each thread its share into its own table, the positions streamed: in region order
// they would be gathered at random across the cloud), the tables then merged region by region;
// and the same over the whole cloud.
double BondedListTrigger::measure(const double* x) {
  ++measured_;
  const std::size_t cells = regions_.occupiedCells(), n = n_;
  region_.resize(kFields * cells);
  double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf}, largest2 = 0.0;
#pragma omp parallel
  {
    const std::size_t teams = static_cast<std::size_t>(threadCount());
    const std::size_t me = static_cast<std::size_t>(threadNumber());
#pragma omp single
    table_.resize(teams * kFields * cells);
    double* mine = table_.data() + me * kFields * cells;
    for (std::size_t c = 0; c < cells; ++c)
      std::copy(kEmpty, kEmpty + kFields, mine + kFields * c);
    for (std::size_t i = n * me / teams; i < n * (me + 1) / teams; ++i) {
      double* r = mine + kFields * regions_.cellOf(i);
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double d = x[3 * i + k] - built_[3 * i + k];
        r[k] = std::min(r[k], d), r[3 + k] = std::max(r[3 + k], d);
        d2 += d * d;
      }
      r[6] = std::max(r[6], d2);
    }
#pragma omp barrier
    double tlo[3] = {kInf, kInf, kInf}, thi[3] = {-kInf, -kInf, -kInf}, tm2 = 0.0;
#pragma omp for schedule(static) nowait
    for (long c = 0; c < static_cast<long>(cells); ++c) {
      double* out = region_.data() + kFields * static_cast<std::size_t>(c);
      std::copy(kEmpty, kEmpty + kFields, out);
      for (std::size_t t = 0; t < teams; ++t) {
        const double* r = table_.data() + (t * cells + static_cast<std::size_t>(c)) * kFields;
        for (int k = 0; k < 3; ++k)
          out[k] = std::min(out[k], r[k]), out[3 + k] = std::max(out[3 + k], r[3 + k]);
        out[6] = std::max(out[6], r[6]);
      }
      for (int k = 0; k < 3; ++k)
        tlo[k] = std::min(tlo[k], out[k]), thi[k] = std::max(thi[k], out[3 + k]);
      tm2 = std::max(tm2, out[6]);
      out[6] = std::sqrt(out[6]);
    }
#pragma omp critical
    {
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], tlo[k]), hi[k] = std::max(hi[k], thi[k]);
      largest2 = std::max(largest2, tm2);
    }
  }
  // Pairs of regions that are not neighbours were at least far_ apart at the build.
  const double farBound =
      std::min(norm3(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 2.0 * std::sqrt(largest2));
  return std::min(reach_ - rEq_ - worstNeighbourBound(), far_ - rEq_ - farBound);
}

// The largest bound on |Δx_i − Δx_j| over the pairs of neighbouring regions (each pair once, a
// region with itself included): the lesser of the norm of the per-axis spans of the two boxes
// and the sum of the two largest displacements.
double BondedListTrigger::worstNeighbourBound() const {
  const long cells = static_cast<long>(regions_.occupiedCells());
  double worst2 = 0.0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(max : worst2)
  for (long c = 0; c < cells; ++c) {
    const double* r = region_.data() + kFields * static_cast<std::size_t>(c);
    for (std::size_t e = neighbourStart_[static_cast<std::size_t>(c)];
         e < neighbourStart_[static_cast<std::size_t>(c) + 1]; ++e) {
      const double* s = region_.data() + kFields * neighbour_[e];
      double box2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double span = std::max(r[3 + k] - s[k], s[3 + k] - r[k]);
        box2 += span * span;
      }
      const double m = r[6] + s[6];
      worst2 = std::max(worst2, std::min(box2, m * m));
    }
  }
  return std::sqrt(worst2);
}

} // namespace craterkit
