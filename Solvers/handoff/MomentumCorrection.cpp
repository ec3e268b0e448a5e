#include "handoff/MomentumCorrection.h"

#include <Eigen/Dense>

namespace craterkit {

namespace {
Eigen::Vector3d vec(const std::vector<double>& a, std::size_t i) {
  return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}
} // namespace

HandoffTotals totalsOf(const ParticleSet& p, const std::vector<std::size_t>* subset) {
  HandoffTotals t;
  const std::size_t n = subset ? subset->size() : p.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = subset ? (*subset)[k] : k;
    const double m = p.mass[i];
    const double* x = &p.position[3 * i];
    const double* v = &p.velocity[3 * i];
    const double* w = &p.angularVelocity[3 * i];
    const double I = 0.4 * m * p.radius[i] * p.radius[i];
    t.mass += m;
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += m * v[a];
    t.angularMomentum[0] += m * (x[1] * v[2] - x[2] * v[1]) + I * w[0];
    t.angularMomentum[1] += m * (x[2] * v[0] - x[0] * v[2]) + I * w[1];
    t.angularMomentum[2] += m * (x[0] * v[1] - x[1] * v[0]) + I * w[2];
  }
  return t;
}

HandoffTotals mappedTarget(const HandoffTotals& compact, const HandoffTotals& curtain) {
  HandoffTotals target = compact;
  target.mass -= curtain.mass;
  for (int a = 0; a < 3; ++a) {
    target.momentum[a] -= curtain.momentum[a];
    target.angularMomentum[a] -= curtain.angularMomentum[a];
  }
  return target;
}

void correctMomentum(ParticleSet& p, const std::vector<std::size_t>& mapped,
                     const HandoffTotals& target, HandoffTotals& before, HandoffTotals& after,
                     std::vector<std::string>& warnings) {
  before = totalsOf(p, &mapped);
  if (mapped.empty()) {
    warnings.push_back("no bed particle lies inside the alpha shape: the compact SPH material's "
                       "momentum is lost");
    after = totalsOf(p, &mapped);
    return;
  }
  Eigen::Vector3d dV;
  for (int a = 0; a < 3; ++a)
    dV(a) = (target.momentum[a] - before.momentum[a]) / before.mass;
  for (std::size_t j : mapped)
    for (int a = 0; a < 3; ++a)
      p.velocity[3 * j + a] += dV(a);
  const HandoffTotals shifted = totalsOf(p, &mapped);
  Eigen::Vector3d cm = Eigen::Vector3d::Zero();
  for (std::size_t j : mapped)
    cm += p.mass[j] * vec(p.position, j);
  cm /= shifted.mass;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (std::size_t j : mapped) {
    const Eigen::Vector3d r = vec(p.position, j) - cm;
    I += p.mass[j] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  Eigen::Vector3d dL;
  for (int a = 0; a < 3; ++a)
    dL(a) = target.angularMomentum[a] - shifted.angularMomentum[a];
  Eigen::FullPivLU<Eigen::Matrix3d> lu(I);
  if (lu.isInvertible()) {
    const Eigen::Vector3d dW = lu.solve(dL);
    for (std::size_t j : mapped) {
      const Eigen::Vector3d add = dW.cross(vec(p.position, j) - cm);
      for (int a = 0; a < 3; ++a)
        p.velocity[3 * j + a] += add(a);
    }
  } else {
    warnings.push_back("the mapped bed particles are collinear: angular momentum could not be "
                       "corrected");
  }
  after = totalsOf(p, &mapped);
}

} // namespace craterkit
