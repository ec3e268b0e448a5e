// The DEM's input checks: parameters and particles are refused before any work, with a message
// that names the property and the first offending particle.
#include "dem/DemSolver.h"

#include "common/Error.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace craterkit {

std::string describeParticle(const ParticleSet& s, std::size_t i) {
  std::ostringstream out;
  out << "particle " << i << " (Id " << s.id[i] << ")";
  return out.str();
}

void DemParams::validate() const {
  contact.validate();
  gravity.validate();
  for (const Wall& w : walls)
    w.validate();
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream msg;
    msg << "TimeStep must be positive and finite (got " << dt << " s)";
    throw InputError(msg.str());
  }
  if (!std::isfinite(skin))
    throw InputError("the Verlet skin must be finite");
  if (walls.size() > 64)
    throw InputError("at most 64 walls are supported");
  if (!(overlapAbort > 0.0) || !(initialOverlapLimit >= 0.0) || !(minStepsPerCollision > 0.0))
    throw InputError("overlap and step limits must be positive");
}

void DemSolver::checkInput() const {
  const ParticleSet& s = state_;
  if (n_ == 0)
    throw InputError("the DEM input has no particles");
  if (n_ > std::numeric_limits<std::uint32_t>::max())
    throw InputError("the DEM supports at most 2^32 - 1 particles");
  if (s.position.size() != 3 * n_ || s.velocity.size() != 3 * n_ ||
      s.angularVelocity.size() != 3 * n_ || s.mass.size() != n_ || s.id.size() != n_)
    throw InputError("the DEM input arrays have inconsistent lengths");
  std::size_t badPos = 0, badVel = 0, badRadius = 0, badMass = 0, first = n_;
  for (std::size_t i = 0; i < n_; ++i) {
    bool bad = false;
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(s.position[3 * i + k])) {
        ++badPos;
        bad = true;
        break;
      }
    }
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.velocity[3 * i + k]) || !std::isfinite(s.angularVelocity[3 * i + k])) {
        ++badVel;
        bad = true;
        break;
      }
    if (!(s.radius[i] > 0.0) || !std::isfinite(s.radius[i])) {
      ++badRadius;
      bad = true;
    }
    if (!(s.mass[i] > 0.0) || !std::isfinite(s.mass[i])) {
      ++badMass;
      bad = true;
    }
    if (bad && first == n_)
      first = i;
  }
  if (first != n_) {
    std::ostringstream msg;
    msg << "bad particles in the DEM input: " << badPos << " with NaN or infinite positions, "
        << badVel << " with NaN or infinite velocities or spins, " << badRadius
        << " with non-positive radii, " << badMass
        << " with non-positive masses (first: " << describeParticle(s, first) << ")";
    throw InputError(msg.str());
  }
}

} // namespace craterkit
