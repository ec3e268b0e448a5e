#include "sph/SupportList.h"

#include "sph/NeighbourList.h"
#include "sph/SimdClones.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {

// The entries of `in` within (1 + kSupportSkin) times the pair's support h̄ = (h_a + h_b)/2 of
// particle `self`, in order, written to `out`; returns their number. Branch-free (every entry
// is written, the kept ones advance) so that the loop vectorises.
CK_SIMD_CLONES std::uint32_t keepNear(const PairPosition* X, std::uint32_t self,
                                      const std::uint32_t* in, std::uint32_t count,
                                      const double period[3], std::uint32_t* out) {
  const PairPosition& A = X[self];
  const double reach = 0.5 * (1.0 + kSupportSkin);
  std::uint32_t m = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t code = in[k], c = code & 31u;
    const PairPosition& B = X[code >> 5];
    const double rx = A.x[0] - B.x[0] - (static_cast<int>(c % 3) - 1) * period[0];
    const double ry = A.x[1] - B.x[1] - (static_cast<int>(c / 3 % 3) - 1) * period[1];
    const double rz = A.x[2] - B.x[2] - (static_cast<int>(c / 9) - 1) * period[2];
    const double hb = reach * (A.h + B.h);
    out[m] = code;
    m += rx * rx + ry * ry + rz * rz < hb * hb;
  }
  return m;
}

} // namespace

bool SupportList::holds(const PairPosition* X, std::size_t n) const {
  // A pair left out was at least (1 + s) h̄ apart at the draw (s = kSupportSkin). It is inside
  // the support only once its particles' displacements d and growths of h, Δh, reach
  // d_a + d_b + (Δh_a + Δh_b)/2 ≥ s h̄ = s (h_a + h_b)/2 (h̄ and h at the draw); so the list
  // holds while every particle has d + max(Δh, 0)/2 below s h/2. The bound keeps a tenth of
  // that for the rounding of the support test.
  const double allow = 0.45 * kSupportSkin;
  bool ok = true;
#pragma omp parallel for schedule(static) reduction(&& : ok) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const PairPosition &a = X[i], &r = ref_[i];
    const double dx = a.x[0] - r.x[0], dy = a.x[1] - r.x[1], dz = a.x[2] - r.x[2];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz) + 0.5 * std::max(a.h - r.h, 0.0);
    ok = ok && d < allow * r.h;
  }
  return ok;
}

void SupportList::draw(const PairPosition* X, std::size_t n, const double period[3],
                       const Source& source) {
  start_.resize(n + 1);
  count_.resize(n);
  std::vector<const std::uint32_t*> from(n);
  start_[0] = 0;
  for (std::size_t a = 0; a < n; ++a) {
    source(a, from[a], count_[a]);
    start_[a + 1] = start_[a] + count_[a];
  }
  entry_.resize(start_[n]);
  ref_.assign(X, X + n);
#pragma omp parallel for schedule(dynamic, 256) if (n >= 512)
  for (std::size_t a = 0; a < n; ++a)
    count_[a] = keepNear(X, static_cast<std::uint32_t>(a), from[a], count_[a], period,
                         entry_.data() + start_[a]);
  ++draws_;
}

bool SupportList::follow(const PairPosition* X, std::size_t n, std::size_t version,
                         const double period[3], const Source& source) {
  if (rest_ > 0) {
    --rest_;
    return false;
  }
  if (drawn_ && version == version_ && ref_.size() == n && holds(X, n)) {
    ++life_;
    return true;
  }
  if (drawn_ && life_ < kSupportLife) {
    drawn_ = false, life_ = 0, rest_ = kSupportRest;
    return false;
  }
  draw(X, n, period, source);
  version_ = version, drawn_ = true, life_ = 1;
  return true;
}

} // namespace craterkit
