#include "bonded/BondedReport.h"

namespace craterkit {

BondedFragmentResult analyseDebrisCloud(const BondedSolver& solver, double massFraction) {
  const BondedSystem& sys = solver.system();
  DebrisCloudParams cloud;
  cloud.axis = sys.axis;
  cloud.cloudStart = sys.rearFace;
  cloud.impactSpeed = sys.impactSpeed;
  cloud.massFraction = massFraction;
  return analyseBondedFragments(sys.positions, sys.velocities, sys.masses, sys.bonds,
                                solver.bondBroken(), cloud);
}

BondedArrays bondedArrays(const BondedSolver& solver, const BondedFragmentResult& frag,
                          double projectileDensity, double plateDensity) {
  const BondedSystem& sys = solver.system();
  const std::size_t n = sys.size();
  BondedArrays a;
  a.radius.assign(n, 0.5 * sys.law.rEq());
  a.material.assign(sys.body.begin(), sys.body.end());
  a.bondCount.assign(n, 0);
  for (std::size_t k = 0; k < sys.bonds.size(); ++k)
    if (!solver.bondBroken()[k])
      ++a.bondCount[sys.bonds[k].i], ++a.bondCount[sys.bonds[k].j];
  a.density.resize(n);
  a.id.resize(n);
  a.fragmentId.resize(n);
  a.internalEnergy.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    a.internalEnergy[i] = solver.internalEnergy()[i] / sys.masses[i];
    a.density[i] = sys.body[i] == 0 ? projectileDensity : plateDensity;
    a.id[i] = static_cast<std::int64_t>(i);
    a.fragmentId[i] = static_cast<int>(frag.fragmentId[i]);
  }
  return a;
}

std::vector<NamedValue> bondedFields(const BondedSolver& solver, const BondedFragmentResult& f,
                                     double massFraction) {
  const BondedSystem& sys = solver.system();
  const BondedEnergies e = solver.energies();
  auto count = [](std::size_t n) { return static_cast<double>(n); };
  // Distance behind the plate's rear face (0 while there is no cloud).
  auto behindPlate = [&](double s) { return f.cloudParticles ? s - sys.rearFace : 0.0; };
  const auto m = solver.momentum();
  return {NamedValue::number("Time", solver.time()),
          NamedValue::number("Step", static_cast<double>(solver.stepCount())),
          NamedValue::number("TimeStep", solver.timeStep()),
          NamedValue::number("BrokenBonds", static_cast<double>(solver.brokenBonds())),
          NamedValue::number("Bonds", count(sys.bonds.size())),
          NamedValue::number("KineticEnergy", e.kinetic),
          NamedValue::number("RepulsiveEnergy", e.repulsive),
          NamedValue::number("BondEnergy", e.bond),
          NamedValue::number("DissipatedEnergy", e.dissipated),
          NamedValue::number("InternalEnergyTotal", e.internal),
          NamedValue::string("Dissipation", dissipationName(solver.params().dissipation)),
          NamedValue::number("TotalEnergy", e.total()),
          NamedValue::number("Fragmentation", f.fragmentation),
          NamedValue::number("Fragments", count(f.fragmentSize.size())),
          NamedValue::number("CloudParticles", count(f.cloudParticles)),
          NamedValue::number("CloudFragments", count(f.cloudFragments)),
          NamedValue::number("CloudMass", f.cloudMass),
          NamedValue::number("LargestCloudFragmentFraction",
                             f.cloudMass > 0.0 ? f.largestCloudFragmentMass / f.cloudMass : 0.0),
          NamedValue::number("CloudMassFraction", massFraction),
          NamedValue::number("DebrisCloudLeadingEdge", behindPlate(f.leadingEdge)),
          NamedValue::number("DebrisCloudRearEdge", behindPlate(f.rearEdge)),
          NamedValue::number("DebrisCloudAxialLength", f.axialLength),
          NamedValue::number("DebrisCloudRadialExtent", f.radialExtent),
          NamedValue::number("DebrisCloudRatio", f.ratio),
          NamedValue::number("DebrisCloudFrontWidth", f.frontWidth),
          NamedValue::number("DebrisCloudFrontSharpness",
                             f.axialLength > 0.0 ? f.frontWidth / f.axialLength : 0.0),
          NamedValue::number("AxialVelocity", f.axialVelocity),
          NamedValue::number("AxialVelocityRatio", f.axialVelocityRatio),
          NamedValue::number("ImpactSpeed", sys.impactSpeed),
          NamedValue::number("PlateRearFace", sys.rearFace),
          NamedValue::number("ParticleSpacing", sys.law.rEq()),
          NamedValue::number("Sigma", sys.law.sigma),
          NamedValue::number("Epsilon", sys.law.epsilon),
          NamedValue::number("Kappa", sys.law.kappa),
          NamedValue::number("CutoffRadius", sys.law.rCut),
          NamedValue::vector("TotalMomentum", {m[0], m[1], m[2]}),
          NamedValue::vector("ImpactAxis", {sys.axis[0], sys.axis[1], sys.axis[2]})};
}

} // namespace craterkit
