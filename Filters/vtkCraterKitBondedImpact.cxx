#include "vtkCraterKitBondedImpact.h"

#include "vtkCraterKitSolverBridge.h"

#include "bonded/BondedFragments.h"
#include "bonded/BondedRun.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCraterKitBondedImpact);

vtkCraterKitBondedImpact::vtkCraterKitBondedImpact()
{
  this->SetNumberOfInputPorts(0);
}
vtkCraterKitBondedImpact::~vtkCraterKitBondedImpact() = default;

int vtkCraterKitBondedImpact::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const std::vector<double> times =
    craterkit::bridge::outputTimes(0.0, this->EndTime, this->OutputInterval, 100000);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
    static_cast<int>(times.size()));
  const double range[2] = { times.front(), times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

void vtkCraterKitBondedImpact::BuildRun()
{
  using namespace craterkit;
  if (!(this->EndTime >= 0.0) || !std::isfinite(this->EndTime))
    throw InputError("EndTime must be a non-negative time in s");
  if (!(this->OutputInterval > 0.0))
    throw InputError("OutputInterval must be positive");
  if (!(this->TimeStep >= 0.0))
    throw InputError("TimeStep must not be negative (0: the paper's 1e-10 s, scaled with sigma)");
  BondedImpactParams p;
  p.diameter = this->Diameter;
  p.shape = this->ProjectileShape == CYLINDER ? ProjectileShape::Cylinder : ProjectileShape::Sphere;
  p.cylinderLengthRatio = this->CylinderLengthRatio;
  p.thicknessRatio = this->ThicknessRatio;
  p.plateWidthRatio = this->PlateWidthRatio;
  p.projectileDensity = this->ProjectileDensity;
  p.plateDensity = this->PlateDensity;
  p.speed = this->ImpactSpeed;
  p.angle = this->ImpactAngle;
  p.spacing = this->Spacing;
  p.particleCount = this->ParticleCount;
  p.epsilon = this->Epsilon;
  p.kappa = this->Kappa;
  p.rCutOverSigma = this->CutoffRatio;
  p.referenceSigma = this->ReferenceSigma;
  p.temperature = this->Temperature;
  p.seed = static_cast<std::uint64_t>(this->Seed);
  BondedSolverParams sp;
  sp.timeStep = this->TimeStep;
  this->Run = std::make_unique<BondedRun>(
    buildBondedImpact(p), sp, static_cast<std::size_t>(std::max(0, this->KeptStates)));
  if (this->ResumeFromCheckpoint && !this->CheckpointFile.empty() &&
    std::ifstream(this->CheckpointFile).good())
    this->Run->resumeFrom(this->CheckpointFile);
}

int vtkCraterKitBondedImpact::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;
  namespace b = craterkit::bridge;

  if (!this->Run || this->GetMTime() > this->RunBuildTime)
  {
    this->Run.reset();
    if (!b::run(this, [&] { this->BuildRun(); }))
      return 0;
    this->RunBuildTime.Modified();
  }
  double t = 0.0;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  t = std::max(0.0, std::min(t, this->EndTime));
  BondedFragmentResult frag;
  const bool ok = b::run(this, [&] {
    const BondedSolver& s = this->Run->advanceTo(
      t, b::progressOf(this), this->CheckpointFile, this->CheckpointInterval);
    const BondedSystem& sys = s.system();
    DebrisCloudParams cloud;
    cloud.axis = sys.axis;
    cloud.cloudStart = sys.rearFace;
    cloud.impactSpeed = sys.impactSpeed;
    frag = analyseBondedFragments(
      sys.positions, sys.velocities, sys.masses, sys.bonds, s.bondBroken(), cloud);
  });
  if (!ok)
  {
    this->Run.reset(); // a failed or aborted run restarts cleanly on the next request
    return 0;
  }

  const BondedSolver& solver = this->Run->solver();
  const BondedSystem& sys = solver.system();
  const std::size_t n = sys.size();
  b::setVertices(output, sys.positions);
  std::vector<int> bondCount(n, 0), material(sys.body.begin(), sys.body.end()), fragment(n);
  for (std::size_t k = 0; k < sys.bonds.size(); ++k)
    if (!solver.bondBroken()[k])
      ++bondCount[sys.bonds[k].i], ++bondCount[sys.bonds[k].j];
  std::vector<double> density(n), radius(n, 0.5 * sys.law.rEq()); // touching at r_eq
  std::vector<std::int64_t> ids(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    density[i] = sys.body[i] == 0 ? this->ProjectileDensity : this->PlateDensity;
    ids[i] = static_cast<std::int64_t>(i);
    fragment[i] = static_cast<int>(frag.fragmentId[i]);
  }
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(b::doubleArray("Velocity", 3, sys.velocities));
  pd->AddArray(b::doubleArray("Radius", 1, radius));
  pd->AddArray(b::doubleArray("Mass", 1, sys.masses));
  pd->AddArray(b::doubleArray("Density", 1, density));
  pd->AddArray(b::intArray("Material", material));
  pd->AddArray(b::idArray("Id", ids));
  pd->AddArray(b::intArray("BondCount", bondCount));
  pd->AddArray(b::intArray("FragmentId", fragment));
  pd->SetActiveScalars("FragmentId");

  vtkFieldData* fd = output->GetFieldData();
  const BondedEnergies e = solver.energies();
  const std::pair<const char*, double> fields[] = { { "Time", solver.time() },
    { "Step", static_cast<double>(solver.stepCount()) }, { "TimeStep", solver.timeStep() },
    { "BrokenBonds", static_cast<double>(solver.brokenBonds()) },
    { "Bonds", static_cast<double>(sys.bonds.size()) }, { "KineticEnergy", e.kinetic },
    { "RepulsiveEnergy", e.repulsive }, { "BondEnergy", e.bond },
    { "DissipatedEnergy", e.dissipated }, { "TotalEnergy", e.total() },
    { "Fragmentation", frag.fragmentation },
    { "Fragments", static_cast<double>(frag.fragmentSize.size()) },
    { "CloudParticles", static_cast<double>(frag.cloudParticles) },
    { "CloudFragments", static_cast<double>(frag.cloudFragments) },
    { "DebrisCloudAxialLength", frag.axialLength },
    { "DebrisCloudRadialExtent", frag.radialExtent }, { "DebrisCloudRatio", frag.ratio },
    { "AxialVelocity", frag.axialVelocity }, { "AxialVelocityRatio", frag.axialVelocityRatio },
    { "ImpactSpeed", sys.impactSpeed }, { "PlateRearFace", sys.rearFace },
    { "ParticleSpacing", sys.law.rEq() }, { "Sigma", sys.law.sigma },
    { "Epsilon", sys.law.epsilon }, { "Kappa", sys.law.kappa }, { "CutoffRadius", sys.law.rCut } };
  for (const auto& field : fields)
    b::addField(fd, field.first, field.second);
  b::addField(fd, "TotalMomentum", solver.momentum().data(), 3);
  b::addField(fd, "ImpactAxis", sys.axis.data(), 3);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitBondedImpact::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const std::pair<const char*, double> values[] = { { "ProjectileShape", this->ProjectileShape },
    { "Diameter", this->Diameter }, { "CylinderLengthRatio", this->CylinderLengthRatio },
    { "ThicknessRatio", this->ThicknessRatio }, { "PlateWidthRatio", this->PlateWidthRatio },
    { "ProjectileDensity", this->ProjectileDensity }, { "PlateDensity", this->PlateDensity },
    { "ImpactSpeed", this->ImpactSpeed }, { "ImpactAngle", this->ImpactAngle },
    { "Spacing", this->Spacing }, { "ParticleCount", this->ParticleCount },
    { "Epsilon", this->Epsilon }, { "Kappa", this->Kappa }, { "CutoffRatio", this->CutoffRatio },
    { "ReferenceSigma", this->ReferenceSigma }, { "Temperature", this->Temperature },
    { "Seed", this->Seed }, { "TimeStep", this->TimeStep }, { "EndTime", this->EndTime },
    { "OutputInterval", this->OutputInterval }, { "CheckpointInterval", this->CheckpointInterval },
    { "ResumeFromCheckpoint", this->ResumeFromCheckpoint }, { "KeptStates", this->KeptStates } };
  for (const auto& value : values)
    os << indent << value.first << ": " << value.second << "\n";
  os << indent << "CheckpointFile: " << this->CheckpointFile << "\n";
}
