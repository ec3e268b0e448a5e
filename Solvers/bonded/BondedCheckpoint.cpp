#include "bonded/BondedCheckpoint.h"

#include "common/CheckpointFormat.h"
#include "common/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <istream>
#include <ostream>
#include <string>

namespace craterkit {
namespace {

const CheckpointKind kBonded{
    "BONDED", "bonded checkpoint", {'C', 'K', 'B', 'O', 'N', 'D', '0', '1'}};

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
    throw InputError("the bonded checkpoint is truncated");
}
template <class T> void getVector(std::istream& in, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  if (!in)
    throw InputError("the bonded checkpoint is truncated");
}

// Every field of the parameters is written by name below: a new one must be added there too.
static_assert(sizeof(BondedSolverParams) == 6 * sizeof(double) + 8,
              "BondedSolverParams changed: write and read its new fields in BondedCheckpoint.cpp");

} // namespace

void BondedSolver::writeCheckpoint(const std::string& path) const {
  writeCheckpointFile(path, kBonded, [&](std::ostream& out) {
    out.write(kBonded.legacyMagic, sizeof kBonded.legacyMagic);
    put(out, static_cast<std::uint64_t>(sys_.size()));
    put(out, static_cast<std::uint64_t>(sys_.bonds.size()));
    put(out, sys_.law);
    put(out, sys_.axis);
    put(out, sys_.rearFace);
    put(out, sys_.impactSpeed);
    // The parameters field by field (no padding bytes): those of version 1 here, the shock
    // heating's at the end.
    put(out, params_.timeStep);
    put(out, params_.timeStepFraction);
    put(out, params_.skin);
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
    put(out, static_cast<std::uint32_t>(params_.dissipation));
    put(out, params_.shockViscosityLinear);
    put(out, params_.shockViscosityQuadratic);
    put(out, params_.shockViscosityThreshold);
    putVector(out,
              internal_.size() == sys_.size() ? internal_ : std::vector<double>(sys_.size(), 0.0));
  });
}

BondedSolver BondedSolver::readCheckpoint(const std::string& path) {
  BondedSolver s;
  readCheckpointFile(path, kBonded, [&](std::istream& in, const CheckpointFrame& frame) {
    char magic[sizeof kBonded.legacyMagic];
    in.read(magic, sizeof magic);
    if (!in || !std::equal(magic, magic + sizeof magic, kBonded.legacyMagic))
      throw InputError("not a bonded checkpoint");
    std::uint64_t n = 0, nb = 0, broken = 0;
    get(in, n);
    get(in, nb);
    if (n == 0 || n >= (1ULL << 32) || nb > 64 * n)
      throw InputError("the bonded checkpoint has implausible sizes");
    // The payload's size is fixed by the counts: checked before anything is allocated.
    const bool heating = frame.version >= 2; // the shock heating's block
    const std::uint64_t fixed = sizeof magic + 4 * sizeof(std::uint64_t) + sizeof(ws2017::Law) +
                                sizeof(std::array<double, 3>) + 7 * sizeof(double) +
                                (heating ? sizeof(std::uint32_t) + 3 * sizeof(double) : 0);
    const std::uint64_t perParticle =
        10 * sizeof(double) + sizeof(std::uint8_t) + (heating ? sizeof(double) : 0);
    constexpr std::uint64_t perBond = sizeof(BondedBond) + sizeof(std::uint8_t);
    if (frame.payloadBytes != fixed + n * perParticle + nb * perBond)
      throw InputError("the bonded checkpoint's size (" + std::to_string(frame.payloadBytes) +
                       " bytes) does not match its " + std::to_string(n) + " particles and " +
                       std::to_string(nb) + " bonds");
    checkBondedMemory(static_cast<double>(n), 0.0, "the bonded checkpoint");
    get(in, s.sys_.law);
    get(in, s.sys_.axis);
    get(in, s.sys_.rearFace);
    get(in, s.sys_.impactSpeed);
    get(in, s.params_.timeStep);
    get(in, s.params_.timeStepFraction);
    get(in, s.params_.skin);
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
    if (heating) {
      std::uint32_t dissipation = 0;
      get(in, dissipation);
      s.params_.dissipation = static_cast<BondedDissipation>(dissipation);
      get(in, s.params_.shockViscosityLinear);
      get(in, s.params_.shockViscosityQuadratic);
      get(in, s.params_.shockViscosityThreshold);
      getVector(in, s.internal_, n);
    } // else the paper's model (version 1 had no shock heating): the defaults, no heat
    s.params_.validate();
    const ws2017::Law& law = s.sys_.law;
    if (!(law.sigma > 0.0 && law.epsilon > 0.0 && law.kappa > 0.0 && law.rCut > law.rEq()) ||
        !std::all_of(s.sys_.masses.begin(), s.sys_.masses.end(), [](double m) { return m > 0.0; }))
      throw InputError("the bonded checkpoint has an invalid law or masses");
    if (!(s.dt_ > 0.0 && std::isfinite(s.dt_)))
      throw InputError("the bonded checkpoint has no valid time step");
    if (!std::all_of(s.sys_.bonds.begin(), s.sys_.bonds.end(),
                     [n](const BondedBond& b) { return b.i < b.j && b.j < n; }) ||
        !std::all_of(s.bondBroken_.begin(), s.bondBroken_.end(),
                     [](std::uint8_t f) { return f <= 1; }))
      throw InputError("the bonded checkpoint has an invalid bond (particles or broken flag)");
    if (!frame.warning.empty())
      s.warnings_.push_back(frame.warning);
  });
  s.prepare(); // forces are the stored ones: the run continues bit for bit
  return s;
}

} // namespace craterkit
