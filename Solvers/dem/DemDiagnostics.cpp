// DemSolver's diagnostics (docs/physics.md §1): kinetic, rotational, gravitational and
// elastic energies (the springs of the normal law, the tangential, rolling and twisting
// springs of every contact and wall contact), momentum and angular momentum, the largest
// speed and overlap, and the pairs in contact. Read-only; no effect on the run.
#include "dem/DemSolver.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {

using Vec = Eigen::Vector3d;
inline Vec at(const std::vector<double>& a, std::size_t i) {
  return Vec(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}

} // namespace

template <class Law>
double DemSolver::elasticEnergyWith(const Law& pairLaw, const Law& wallLaw) const {
  const ContactParams& cp = params_.contact;
  const double kT = cp.tangentialStiffness();
  const ParticleSet& s = state_;
  double e = 0.0;
  auto springs = [&](const ContactHistory& h, double overlap, double rbar, const Law& law) {
    const Eigen::Map<const Vec> S(h.spring), xi(h.rolling);
    const double br = cp.beta * rbar;
    return law.energy(overlap, rbar) + 0.5 * kT * S.squaredNorm() +
           0.5 * law.stiffness(overlap, rbar) * br * br * xi.squaredNorm() +
           0.5 * 2.0 * kT * br * br * h.twisting * h.twisting;
  };
  const ContactTable& table = tables_[current_];
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::size_t i = pairs_.first[k], j = pairs_.second[k];
    const double d = (at(s.position, j) - at(s.position, i)).norm();
    const double overlap = s.radius[i] + s.radius[j] - d;
    if (overlap > 0.0)
      e += springs(pairs_.active[k] ? table.historyAt(pairs_.row[k]) : ContactHistory{}, overlap,
                   s.radius[i] * s.radius[j] / (s.radius[i] + s.radius[j]), pairLaw);
  }
  // Every wall a particle touches is among its entries (they are refreshed with the list).
  const WallContacts& wc = wallContacts_;
  for (std::size_t c = 0; c < wc.size(); ++c) {
    const std::size_t i = wc.particle[c];
    double nv[3], lever;
    const double overlap =
        params_.walls[wc.wall[c]].overlap(&s.position[3 * i], s.radius[i], nv, lever);
    if (overlap > 0.0)
      e += springs(wc.history[c], overlap, s.radius[i], wallLaw);
  }
  return e;
}

DemDiagnostics DemSolver::diagnostics() const {
  DemDiagnostics d;
  d.time = time_;
  d.step = step_;
  const ParticleSet& s = state_;
  for (std::size_t i = 0; i < n_; ++i) {
    const Vec x = at(s.position, i), v = at(s.velocity, i), w = at(s.angularVelocity, i);
    d.kineticEnergy += 0.5 * s.mass[i] * v.squaredNorm();
    d.rotationalEnergy += 0.5 * inertia_[i] * w.squaredNorm();
    d.gravitationalEnergy += s.mass[i] * params_.gravity.potential(&s.position[3 * i]);
    d.momentum += s.mass[i] * v;
    d.angularMomentum += s.mass[i] * x.cross(v) + inertia_[i] * w;
    d.maxSpeed = std::max(d.maxSpeed, v.norm());
  }
  const ContactParams& c = params_.contact;
  if (c.normalModel == "Hertz") {
    const double E = c.youngsModulus / (1.0 - c.poissonRatio * c.poissonRatio);
    d.elasticEnergy = elasticEnergyWith(Hertz{0.5 * E, dampingFactorN_, c.poissonRatio},
                                        Hertz{E, dampingFactorN_, c.poissonRatio});
  } else {
    const LinearSpringDashpot law{c.kN, dampingFactorN_};
    d.elasticEnergy = elasticEnergyWith(law, law);
  }
  d.maxOverlap = worstOverlap_;
  for (char a : pairs_.active)
    d.contacts += a != 0;
  for (char a : wallContacts_.active)
    d.wallContacts += a != 0;
  return d;
}

std::vector<std::pair<std::size_t, std::size_t>> DemSolver::contactPairs() const {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  const ParticleSet& s = state_;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::size_t i = pairs_.first[k], j = pairs_.second[k];
    if ((at(s.position, j) - at(s.position, i)).norm() < s.radius[i] + s.radius[j])
      out.emplace_back(i, j);
  }
  return out;
}

} // namespace craterkit
