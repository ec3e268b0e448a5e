#include "sph/SphRun.h"

#include "common/AtomicWrite.h"
#include "common/Error.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

namespace craterkit {

namespace {
constexpr char kMagic[8] = {'C', 'K', 'S', 'P', 'H', '1', '\n', '\0'};

template <class T> void put(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
void get(std::ifstream& in, std::vector<T>& v, std::size_t n, const std::string& path) {
  v.resize(n);
  if (!in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T))))
    throw InputError(path + ": the SPH checkpoint is truncated");
}
} // namespace

void writeSphCheckpoint(const std::string& path, const SphState& s, double time, std::size_t steps,
                        double nextStep) {
  writeFileAtomically(path, "the SPH checkpoint", [&](std::ostream& out) {
    out.write(kMagic, sizeof kMagic);
    const std::uint64_t head[2] = {s.size(), steps};
    out.write(reinterpret_cast<const char*>(head), sizeof head);
    out.write(reinterpret_cast<const char*>(&time), sizeof time);
    out.write(reinterpret_cast<const char*>(&nextStep), sizeof nextStep);
    put(out, s.x), put(out, s.v), put(out, s.mass), put(out, s.rho), put(out, s.u), put(out, s.h);
    put(out, s.S), put(out, s.alpha), put(out, s.damage);
    std::vector<std::int32_t> mat(s.material.begin(), s.material.end());
    put(out, mat);
  });
}

SphState readSphCheckpoint(const std::string& path, double& time, std::size_t& steps,
                           double& nextStep) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path + ": cannot open the SPH checkpoint");
  in.seekg(0, std::ios::end);
  const std::uint64_t bytes = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  char magic[8];
  std::uint64_t head[2];
  if (bytes < 8 || !in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(path + ": not a CraterKit SPH checkpoint (bad magic)");
  if (!in.read(reinterpret_cast<char*>(head), sizeof head) ||
      !in.read(reinterpret_cast<char*>(&time), sizeof time) ||
      !in.read(reinterpret_cast<char*>(&nextStep), sizeof nextStep))
    throw InputError(path + ": the SPH checkpoint header is truncated");
  const std::uint64_t n = head[0];
  const std::uint64_t perParticle = 8 * (3 + 3 + 4 + 6 + 2) + 4;
  constexpr std::uint64_t header = 40;
  if (bytes < header || n == 0 || n > (bytes - header) / perParticle ||
      (bytes - header) != n * perParticle)
    throw InputError(path + ": the SPH checkpoint's particle count (" + std::to_string(n) +
                     ") does not match its size of " + std::to_string(bytes) + " bytes");
  if (!std::isfinite(time) || !(nextStep > 0.0) || !std::isfinite(nextStep))
    throw InputError(path +
                     ": the SPH checkpoint's time or time step is not a finite positive number");
  steps = head[1];
  SphState s;
  get(in, s.x, 3 * n, path), get(in, s.v, 3 * n, path), get(in, s.mass, n, path),
      get(in, s.rho, n, path);
  get(in, s.u, n, path), get(in, s.h, n, path), get(in, s.S, 6 * n, path),
      get(in, s.alpha, n, path);
  get(in, s.damage, n, path);
  std::vector<std::int32_t> mat;
  get(in, mat, n, path);
  s.material.assign(mat.begin(), mat.end());
  return s;
}

SphRun::SphRun(const SphState& initial, const SphParams& params, std::size_t keptStates)
    : TimeDrivenRun(std::make_unique<SphSolver>(initial, params), keptStates,
                    -std::numeric_limits<double>::infinity()),
      initial_(initial), params_(params) {}

const SphSolver& SphRun::advanceTo(double time, const ProgressCallback& progress,
                                   const std::string& checkpointPath, long long checkpointEvery) {
  goBackTo(
      time, solver_->time(), [&] { return std::make_unique<SphSolver>(initial_, params_); },
      [&](const SphKeptState& kept) {
        return std::make_unique<SphSolver>(kept.state, params_,
                                           SphClock{kept.time, kept.steps, kept.nextStep});
      });
  const double from = solver_->time();
  std::size_t lastCheckpoint = solver_->steps();
  const auto checkpoint = [&] {
    writeSphCheckpoint(checkpointPath, solver_->state(), solver_->time(), solver_->steps(),
                       solver_->stableStep());
    checkpointReached(solver_->time());
  };
  while (!solver_->reached(time)) {
    const double dt = std::min(solver_->stableStep(), time - solver_->time());
    solver_->step(dt);
    // A state behind the file's (a request for an earlier time) never overwrites it.
    if (!checkpointPath.empty() && checkpointEvery > 0 && aheadOfCheckpoint(solver_->time()) &&
        solver_->steps() - lastCheckpoint >= static_cast<std::size_t>(checkpointEvery)) {
      checkpoint();
      lastCheckpoint = solver_->steps();
    }
    reportProgress(progress, (solver_->time() - from) / (time - from));
  }
  if (!checkpointPath.empty() && checkpointEvery > 0 && solver_->steps() != lastCheckpoint &&
      aheadOfCheckpoint(solver_->time()))
    checkpoint();
  keep(solver_->time(), [&] {
    return SphKeptState{solver_->state(), solver_->time(), solver_->steps(), solver_->stableStep()};
  });
  return *solver_;
}

void SphRun::resumeFrom(const std::string& checkpointPath) {
  double t = 0.0, next = 0.0;
  std::size_t steps = 0;
  const SphState s = readSphCheckpoint(checkpointPath, t, steps, next);
  if (s.size() != initial_.size())
    throw InputError(checkpointPath + ": the checkpoint has " + std::to_string(s.size()) +
                     " particles, this set-up " + std::to_string(initial_.size()));
  for (int m : s.material)
    if (m < 0 || static_cast<std::size_t>(m) >= params_.materials.size())
      throw InputError(checkpointPath +
                       ": the checkpoint names a material this set-up does not have");
  resumed(std::make_unique<SphSolver>(s, params_, SphClock{t, steps, next}), t);
}

} // namespace craterkit
