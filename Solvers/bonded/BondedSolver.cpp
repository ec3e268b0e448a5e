#include "bonded/BondedSolver.h"

#include "common/AtomicWrite.h"
#include "common/CellList.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace craterkit {
namespace {

// Sum of f(i) over [0, n) in chunks of fixed size, chunk sums added in chunk order: the same
// bits for any number of threads.
template <class F> double chunkedSum(std::size_t n, F&& f) {
  constexpr std::size_t kChunk = 1024;
  const long chunks = static_cast<long>((n + kChunk - 1) / kChunk);
  std::vector<double> part(static_cast<std::size_t>(chunks), 0.0);
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c) {
    const std::size_t end = std::min(n, (static_cast<std::size_t>(c) + 1) * kChunk);
    double s = 0.0;
    for (std::size_t i = static_cast<std::size_t>(c) * kChunk; i < end; ++i)
      s += f(i);
    part[static_cast<std::size_t>(c)] = s;
  }
  double total = 0.0;
  for (double p : part)
    total += p;
  return total;
}

constexpr char kMagic[8] = {'C', 'K', 'B', 'O', 'N', 'D', '0', '1'};

template <class T> void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T> void putVector(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T> void get(std::istream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof(T));
  if (!in)
    throw InputError("bonded checkpoint: file truncated or not a bonded checkpoint");
}
template <class T> void getVector(std::istream& in, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  if (!in)
    throw InputError("bonded checkpoint: file truncated or not a bonded checkpoint");
}

} // namespace

void BondedSolverParams::validate() const {
  if (!(timeStep >= 0.0) || !std::isfinite(timeStep))
    throw InputError("BondedSolver: TimeStep must not be negative");
  if (!(timeStepFraction > 0.0 && timeStepFraction < 0.1))
    throw InputError("BondedSolver: TimeStepFraction must lie in (0, 0.1) of the bond period");
  if (!(skin > 0.0 && skin < 10.0))
    throw InputError("BondedSolver: Skin must lie in (0, 10) sigma");
}

BondedSolver::BondedSolver(BondedSystem system, const BondedSolverParams& params)
    : sys_(std::move(system)), params_(params) {
  params_.validate();
  const std::size_t n = sys_.size();
  if (sys_.positions.size() != 3 * n || sys_.velocities.size() != 3 * n || sys_.body.size() != n)
    throw InputError("BondedSolver: positions, velocities, masses and bodies differ in size");
  if (n == 0)
    throw InputError("BondedSolver: no particles");
  const double mMin = *std::min_element(sys_.masses.begin(), sys_.masses.end());
  if (!(mMin > 0.0) || !(sys_.law.kappa > 0.0) || !(sys_.law.epsilon > 0.0))
    throw InputError("BondedSolver: masses, Kappa and Epsilon must be positive");
  const double period = ws2017::bondPeriod(mMin, sys_.law.kappa);
  dt_ = params_.timeStep > 0.0 ? params_.timeStep : params_.timeStepFraction * period;
  bondBroken_.assign(sys_.bonds.size(), 0);
  force_.assign(3 * n, 0.0);
  prepare();
  computeForces();
}

// Bond adjacency (each particle's bonds in index order) and the neighbour list.
void BondedSolver::prepare() {
  const std::size_t n = sys_.size();
  for (const BondedBond& b : sys_.bonds)
    if (b.i >= n || b.j >= n || b.i == b.j)
      throw InputError("BondedSolver: a bond names a particle that does not exist");
  bondStart_.assign(n + 1, 0);
  for (const BondedBond& b : sys_.bonds) {
    ++bondStart_[b.i + 1];
    ++bondStart_[b.j + 1];
  }
  for (std::size_t i = 0; i < n; ++i)
    bondStart_[i + 1] += bondStart_[i];
  bondsOf_.resize(bondStart_[n]);
  std::vector<std::size_t> fill(bondStart_.begin(), bondStart_.end() - 1);
  for (std::size_t b = 0; b < sys_.bonds.size(); ++b) {
    bondsOf_[fill[sys_.bonds[b].i]++] = static_cast<std::uint32_t>(b);
    bondsOf_[fill[sys_.bonds[b].j]++] = static_cast<std::uint32_t>(b);
  }
  bondForce_.assign(3 * sys_.bonds.size(), 0.0);
  buildNeighbours();
}

void BondedSolver::buildNeighbours() {
  const std::size_t n = sys_.size();
  const double* x = sys_.positions.data();
  const double reach = sys_.law.rEq() + params_.skin * sys_.law.sigma, reach2 = reach * reach;
  CellList cells;
  cells.build(x, n, reach);
  neighbourStart_.assign(n + 1, 0);
  auto scan = [&](std::size_t i, auto&& take) {
    cells.forEachCandidate(x + 3 * i, reach, [&](std::size_t j) {
      const double dx = x[3 * j] - x[3 * i], dy = x[3 * j + 1] - x[3 * i + 1],
                   dz = x[3 * j + 2] - x[3 * i + 2];
      if (j != i && dx * dx + dy * dy + dz * dz < reach2)
        take(j);
    });
  };
  const long nl = static_cast<long>(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < nl; ++i) {
    std::size_t count = 0;
    scan(static_cast<std::size_t>(i), [&](std::size_t) { ++count; });
    neighbourStart_[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i)
    neighbourStart_[i + 1] += neighbourStart_[i];
  neighbours_.resize(neighbourStart_[n]);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < nl; ++i) {
    std::size_t at = neighbourStart_[i];
    scan(static_cast<std::size_t>(i),
         [&](std::size_t j) { neighbours_[at++] = static_cast<std::uint32_t>(j); });
    std::sort(neighbours_.begin() + neighbourStart_[i], neighbours_.begin() + at);
  }
  listOrigin_ = sys_.positions;
}

bool BondedSolver::needsRebuild() const {
  const double half = 0.5 * params_.skin * sys_.law.sigma, limit = half * half;
  const long n3 = static_cast<long>(sys_.positions.size());
  const double* x = sys_.positions.data();
  const double* o = listOrigin_.data();
  double worst = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst)
  for (long k = 0; k < n3; k += 3) {
    const double dx = x[k] - o[k], dy = x[k + 1] - o[k + 1], dz = x[k + 2] - o[k + 2];
    worst = std::max(worst, dx * dx + dy * dy + dz * dz);
  }
  return worst > limit;
}

void BondedSolver::computeForces() {
  const double* x = sys_.positions.data();
  const ws2017::Law& law = sys_.law;
  const double rc2 = law.rCut * law.rCut;
  const long nb = static_cast<long>(sys_.bonds.size());
  long newlyBroken = 0;
#pragma omp parallel for schedule(static) reduction(+ : newlyBroken)
  for (long b = 0; b < nb; ++b) {
    double* fb = &bondForce_[3 * b];
    fb[0] = fb[1] = fb[2] = 0.0;
    if (bondBroken_[b])
      continue;
    const BondedBond& bond = sys_.bonds[b];
    const double dx = x[3 * bond.j] - x[3 * bond.i], dy = x[3 * bond.j + 1] - x[3 * bond.i + 1],
                 dz = x[3 * bond.j + 2] - x[3 * bond.i + 2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 > rc2) { // broken for good (Section 2.2.2)
      bondBroken_[b] = 2;
      ++newlyBroken;
      continue;
    }
    double fOverR;
    ws2017::bondSpring(std::sqrt(r2), bond.rest, law.kappa, fOverR);
    fb[0] = fOverR * dx;
    fb[1] = fOverR * dy;
    fb[2] = fOverR * dz;
  }
  if (newlyBroken > 0)
    bookBreaks();

  const double rEq2 = law.rEq() * law.rEq(), sigma2 = law.sigma * law.sigma;
  const long n = static_cast<long>(sys_.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    double f[3] = {0.0, 0.0, 0.0};
    const double* xi = x + 3 * i;
    for (std::size_t s = neighbourStart_[i]; s < neighbourStart_[i + 1]; ++s) {
      const double* xj = x + 3 * static_cast<std::size_t>(neighbours_[s]);
      const double dx = xi[0] - xj[0], dy = xi[1] - xj[1], dz = xi[2] - xj[2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (!(r2 < rEq2))
        continue;
      double fOverR;
      ws2017::repulsion(r2, sigma2, law.epsilon, fOverR);
      f[0] += fOverR * dx;
      f[1] += fOverR * dy;
      f[2] += fOverR * dz;
    }
    for (std::size_t s = bondStart_[i]; s < bondStart_[i + 1]; ++s) {
      const std::uint32_t b = bondsOf_[s];
      const double* fb = &bondForce_[3 * static_cast<std::size_t>(b)];
      const double sign = sys_.bonds[b].i == static_cast<std::uint32_t>(i) ? 1.0 : -1.0;
      f[0] += sign * fb[0];
      f[1] += sign * fb[1];
      f[2] += sign * fb[2];
    }
    force_[3 * i] = f[0];
    force_[3 * i + 1] = f[1];
    force_[3 * i + 2] = f[2];
  }
}

// Serial and in bond order, so the dissipated energy has the same bits for any thread count.
void BondedSolver::bookBreaks() {
  const double* x = sys_.positions.data();
  for (std::size_t b = 0; b < sys_.bonds.size(); ++b) {
    if (bondBroken_[b] != 2)
      continue;
    const BondedBond& bond = sys_.bonds[b];
    const double dx = x[3 * bond.j] - x[3 * bond.i], dy = x[3 * bond.j + 1] - x[3 * bond.i + 1],
                 dz = x[3 * bond.j + 2] - x[3 * bond.i + 2];
    double unused;
    dissipated_ += ws2017::bondSpring(std::sqrt(dx * dx + dy * dy + dz * dz), bond.rest,
                                      sys_.law.kappa, unused);
    bondBroken_[b] = 1;
    ++broken_;
  }
}

void BondedSolver::step() {
  const long n = static_cast<long>(sys_.size());
  double* x = sys_.positions.data();
  double* v = sys_.velocities.data();
  const double* m = sys_.masses.data();
  const double dt = dt_;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double h = 0.5 * dt / m[i];
    for (int k = 0; k < 3; ++k) {
      v[3 * i + k] += h * force_[3 * i + k];
      x[3 * i + k] += dt * v[3 * i + k];
    }
  }
  if (needsRebuild())
    buildNeighbours();
  computeForces();
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double h = 0.5 * dt / m[i];
    for (int k = 0; k < 3; ++k)
      v[3 * i + k] += h * force_[3 * i + k];
  }
  ++step_;
}

void BondedSolver::advance(std::size_t steps, const ProgressCallback& progress) {
  reportProgress(progress, 0.0);
  const std::size_t every = std::max<std::size_t>(1, steps / 100);
  for (std::size_t s = 1; s <= steps; ++s) {
    step();
    if (s % every == 0 || s == steps)
      reportProgress(progress, static_cast<double>(s) / static_cast<double>(steps));
  }
}

void BondedSolver::advanceTo(double t, const ProgressCallback& progress) {
  if (!std::isfinite(t))
    throw InputError("BondedSolver: the target time must be finite");
  const double target = std::ceil(t / dt_ * (1.0 - 1e-12));
  if (target > static_cast<double>(step_))
    advance(static_cast<std::size_t>(target - static_cast<double>(step_)), progress);
}

BondedEnergies BondedSolver::energies() const {
  BondedEnergies e;
  const double* x = sys_.positions.data();
  const double* v = sys_.velocities.data();
  e.kinetic = chunkedSum(sys_.size(), [&](std::size_t i) {
    const double* vi = v + 3 * i;
    return 0.5 * sys_.masses[i] * (vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
  });
  const ws2017::Law& law = sys_.law;
  const double rEq2 = law.rEq() * law.rEq(), sigma2 = law.sigma * law.sigma;
  e.repulsive = chunkedSum(sys_.size(), [&](std::size_t i) {
    double s = 0.0, unused;
    for (std::size_t k = neighbourStart_[i]; k < neighbourStart_[i + 1]; ++k) {
      const std::size_t j = neighbours_[k];
      const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                   dz = x[3 * i + 2] - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (j > i && r2 < rEq2)
        s += ws2017::repulsion(r2, sigma2, law.epsilon, unused);
    }
    return s;
  });
  e.bond = chunkedSum(sys_.bonds.size(), [&](std::size_t b) {
    if (bondBroken_[b])
      return 0.0;
    const BondedBond& bond = sys_.bonds[b];
    const double dx = x[3 * bond.j] - x[3 * bond.i], dy = x[3 * bond.j + 1] - x[3 * bond.i + 1],
                 dz = x[3 * bond.j + 2] - x[3 * bond.i + 2];
    double unused;
    return ws2017::bondSpring(std::sqrt(dx * dx + dy * dy + dz * dz), bond.rest, law.kappa, unused);
  });
  e.dissipated = dissipated_;
  return e;
}

std::array<double, 3> BondedSolver::momentum() const {
  std::array<double, 3> p{};
  for (int k = 0; k < 3; ++k)
    p[k] = chunkedSum(sys_.size(),
                      [&](std::size_t i) { return sys_.masses[i] * sys_.velocities[3 * i + k]; });
  return p;
}

void BondedSolver::writeCheckpoint(const std::string& path) const {
  writeFileAtomically(path, "the bonded checkpoint", [&](std::ostream& out) {
    out.write(kMagic, sizeof kMagic);
    put(out, static_cast<std::uint64_t>(sys_.size()));
    put(out, static_cast<std::uint64_t>(sys_.bonds.size()));
    put(out, sys_.law);
    put(out, sys_.axis);
    put(out, sys_.rearFace);
    put(out, sys_.impactSpeed);
    put(out, params_);
    put(out, dt_);
    put(out, step_);
    put(out, static_cast<std::uint64_t>(broken_));
    put(out, dissipated_);
    putVector(out, sys_.positions);
    putVector(out, sys_.velocities);
    putVector(out, force_);
    putVector(out, sys_.masses);
    putVector(out, sys_.body);
    putVector(out, sys_.bonds);
    putVector(out, bondBroken_);
  });
}

BondedSolver BondedSolver::readCheckpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError("bonded checkpoint: cannot open '" + path + "'");
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError("bonded checkpoint: '" + path + "' is not a bonded checkpoint");
  BondedSolver s;
  std::uint64_t n = 0, nb = 0, broken = 0;
  get(in, n);
  get(in, nb);
  if (n == 0 || n >= (1ULL << 32) || nb > 64 * n)
    throw InputError("bonded checkpoint: '" + path + "' has implausible sizes");
  checkBondedMemory(static_cast<double>(n), 0.0, "the bonded checkpoint");
  get(in, s.sys_.law);
  get(in, s.sys_.axis);
  get(in, s.sys_.rearFace);
  get(in, s.sys_.impactSpeed);
  get(in, s.params_);
  get(in, s.dt_);
  get(in, s.step_);
  get(in, broken);
  get(in, s.dissipated_);
  s.broken_ = static_cast<std::size_t>(broken);
  getVector(in, s.sys_.positions, 3 * n);
  getVector(in, s.sys_.velocities, 3 * n);
  getVector(in, s.force_, 3 * n);
  getVector(in, s.sys_.masses, n);
  getVector(in, s.sys_.body, n);
  getVector(in, s.sys_.bonds, nb);
  getVector(in, s.bondBroken_, nb);
  s.params_.validate();
  const ws2017::Law& law = s.sys_.law;
  if (!(law.sigma > 0.0 && law.epsilon > 0.0 && law.kappa > 0.0 && law.rCut > law.rEq()) ||
      !std::all_of(s.sys_.masses.begin(), s.sys_.masses.end(), [](double m) { return m > 0.0; }))
    throw InputError("bonded checkpoint: '" + path + "' has an invalid law or masses");
  if (!(s.dt_ > 0.0))
    throw InputError("bonded checkpoint: '" + path + "' has no valid time step");
  s.prepare(); // forces are the stored ones: the run continues bit for bit
  return s;
}

} // namespace craterkit
