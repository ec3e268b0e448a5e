#include "sph/GradyKippFracture.h"

#include "common/Random.h"
#include "sph/SphSolver.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace craterkit {

void GradyKippFracture::assignFlaws(const SphState& s, const std::vector<Material>& materials,
                                    std::uint64_t seed) {
  const std::size_t n = s.size();
  std::vector<std::vector<double>> flaws(n);
  Random rng(seed);
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const Material& mat = materials[m];
    if (!(mat.weibullK > 0.0))
      continue;
    std::vector<std::size_t> members;
    double volume = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (static_cast<std::size_t>(s.material[i]) == m)
        members.push_back(i), volume += s.mass[i] / s.rho[i];
    if (members.empty())
      continue;
    const double count = static_cast<double>(members.size());
    const std::size_t total = static_cast<std::size_t>(std::max(count, count * std::log(count)));
    std::size_t j = 1;
    auto threshold = [&](std::size_t jj) {
      return std::pow(static_cast<double>(jj) / (mat.weibullK * volume), 1.0 / mat.weibullM);
    };
    for (; j <= total; ++j) {
      const auto to = std::min(members.size() - 1, static_cast<std::size_t>(rng.uniform() * count));
      flaws[members[to]].push_back(threshold(j));
    }
    for (std::size_t i : members)
      if (flaws[i].empty())
        flaws[i].push_back(threshold(j++));
  }
  start_.assign(n + 1, 0);
  eps_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    eps_.insert(eps_.end(), flaws[i].begin(), flaws[i].end());
    start_[i + 1] = static_cast<std::uint32_t>(eps_.size());
  }
}

void GradyKippFracture::damageRate(std::size_t a, const Material& mat, const double* Sa, double p,
                                   double D, double rho, double mass, double& rate,
                                   double& cap) const {
  // The local strain from the largest principal (tensile) stress.
  Eigen::Matrix3d sigma;
  sigma << Sa[0] - p, Sa[3], Sa[4], Sa[3], Sa[1] - p, Sa[5], Sa[4], Sa[5], Sa[2] - p;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(sigma, Eigen::EigenvaluesOnly);
  const double s1 = eig.eigenvalues()(2);
  const double Kb = mat.bulkModulus, Gm = mat.shearModulus, E = 9.0 * Kb * Gm / (3.0 * Kb + Gm);
  rate = 0.0, cap = 0.0;
  if (s1 > 0.0 && D < 1.0) {
    const double eps = s1 / ((1.0 - D) * E);
    const double* f0 = &eps_[start_[a]];
    const double* f1 = &eps_[start_[a + 1]];
    const std::size_t active = static_cast<std::size_t>(std::upper_bound(f0, f1, eps) - f0);
    if (active > 0) {
      const double cg = 0.4 * std::sqrt((Kb + 4.0 * Gm / 3.0) / rho);
      const double Rs = std::cbrt(3.0 * mass / (4.0 * M_PI * rho));
      rate = static_cast<double>(active) * cg / Rs;
      cap = static_cast<double>(active) / static_cast<double>(f1 - f0);
    }
  }
}

void GradyKippFracture::integrate(std::vector<double>& damage, const std::vector<double>& from,
                                  double dt, const DamageRates& a, const DamageRates* b) {
  if (a.rate.empty())
    return;
  const long n = static_cast<long>(damage.size());
  // Each particle on its own: any thread count gives the serial loop's bits.
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (long i = 0; i < n; ++i) {
    const double rate = b ? 0.5 * (a.rate[i] + b->rate[i]) : a.rate[i];
    if (rate <= 0.0)
      continue;
    const double cap = b ? std::max(a.cap[i], b->cap[i]) : a.cap[i];
    const double c = std::cbrt(from[i]) + dt * rate;
    damage[i] = std::max(from[i], std::min({c * c * c, cap, 1.0})); // damage never heals
  }
}

} // namespace craterkit
