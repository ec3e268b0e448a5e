#include "bonded/WatsonSteinhauser2017.h"

#include <cmath>

namespace craterkit {
namespace ws2017 {

Sizing sizingOf(const Law& law) {
  Sizing s;
  s.gamma = law.epsilon / (law.sigma * law.sigma * law.sigma);
  s.lambda = law.kappa / law.sigma;
  s.rCutOverSigma = law.rCut / law.sigma;
  return s;
}

Law sizedLaw(const Sizing& sizing, double sigma) {
  Law law;
  law.sigma = sigma;
  law.epsilon = sizing.gamma * sigma * sigma * sigma;
  law.kappa = sizing.lambda * sigma;
  law.rCut = sizing.rCutOverSigma * sigma;
  return law;
}

double particleMass(double bodyMass, std::size_t count) {
  return bodyMass / static_cast<double>(count);
}

double bondPeriod(double mass, double kappa) { return 2.0 * M_PI * std::sqrt(mass / kappa); }

double headlineSigma() {
  const double d = kHeadlineDiameter;
  const double w = kHeadlinePlateWidthRatio * d;
  const double volume = M_PI / 6.0 * d * d * d + kHeadlineThicknessRatio * d * w * w;
  return std::cbrt(volume / kHeadlineParticles) / kTwoToOneSixth;
}

double referenceTimeStepFraction() {
  const double a = kTwoToOneSixth * headlineSigma();
  return kHeadlineTimeStep / bondPeriod(kHeadlineDensity * a * a * a, kHeadlineKappa);
}

} // namespace ws2017
} // namespace craterkit
