#include "vtkCraterKitBondedImpact.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "bonded/BondedFragments.h"
#include "bonded/BondedReport.h"
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

vtkCraterKitBondedImpact::vtkCraterKitBondedImpact() { this->SetNumberOfInputPorts(0); }
vtkCraterKitBondedImpact::~vtkCraterKitBondedImpact() = default;

int vtkCraterKitBondedImpact::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                 vtkInformationVector* outputVector) {
  craterkit::bridge::setTimeSteps(
      outputVector->GetInformationObject(0),
      craterkit::bridge::outputTimes(0.0, this->EndTime, this->OutputInterval, 100000));
  return 1;
}

void vtkCraterKitBondedImpact::BuildRun() {
  using namespace craterkit;
  if (!(this->EndTime >= 0.0) || !std::isfinite(this->EndTime))
    throw InputError("EndTime must be a non-negative time in s");
  if (!(this->OutputInterval > 0.0))
    throw InputError("OutputInterval must be positive");
  if (!(this->TimeStep >= 0.0))
    throw InputError("TimeStep must not be negative (0: the paper's 1e-10 s, scaled with sigma)");
  BondedImpactParams p;
  p.diameter = this->Diameter;
  p.shape = enums::kProjectileShape.toSolver(this->ProjectileShape);
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
  sp.dissipation = enums::kDissipation.toSolver(this->Dissipation);
  sp.shockViscosityLinear = this->ShockViscosityLinear;
  sp.shockViscosityQuadratic = this->ShockViscosityQuadratic;
  sp.shockViscosityThreshold = this->ShockViscosityThreshold;
  sp.validate(); // refused by name before the set-up is built
  this->Run = std::make_unique<BondedRun>(buildBondedImpact(p), sp,
                                          static_cast<std::size_t>(std::max(0, this->KeptStates)));
  craterkit::bridge::resumeIfAsked(*this->Run, this->ResumeFromCheckpoint != 0,
                                   this->CheckpointFile);
  // A resume from an old checkpoint, without a checksum, warns.
  for (const std::string& w : this->Run->solver().warnings())
    vtkWarningMacro(<< w);
}

int vtkCraterKitBondedImpact::RequestData(vtkInformation*, vtkInformationVector**,
                                          vtkInformationVector* outputVector) {
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;
  namespace b = craterkit::bridge;

  if (!b::ensureRun(this, this->Run, this->RunBuildTime, false, [&] { this->BuildRun(); }))
    return 0;
  const double t = std::max(0.0, std::min(b::requestedTime(outInfo, 0.0), this->EndTime));
  BondedFragmentResult frag;
  const bool ok = b::run(this, [&] {
    frag = analyseDebrisCloud(this->Run->advanceTo(t, b::progressOf(this), this->CheckpointFile,
                                                   this->CheckpointInterval),
                              this->CloudMassFraction);
  });
  if (!ok) {
    this->Run.reset(); // a failed or aborted run restarts cleanly on the next request
    return 0;
  }
  const BondedSolver& solver = this->Run->solver();
  const BondedArrays a = bondedArrays(solver, frag, this->ProjectileDensity, this->PlateDensity);
  b::setVertices(output, solver.system().positions);
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(b::doubleArray("Velocity", 3, solver.system().velocities));
  pd->AddArray(b::doubleArray("Radius", 1, a.radius));
  pd->AddArray(b::doubleArray("Mass", 1, solver.system().masses));
  pd->AddArray(b::doubleArray("Density", 1, a.density));
  pd->AddArray(b::intArray("Material", a.material));
  pd->AddArray(b::idArray("Id", a.id));
  pd->AddArray(b::intArray("BondCount", a.bondCount));
  pd->AddArray(b::intArray("FragmentId", a.fragmentId));
  pd->AddArray(b::doubleArray("InternalEnergy", 1, a.internalEnergy));
  pd->SetActiveScalars("FragmentId");
  b::addFields(output->GetFieldData(), bondedFields(solver, frag, this->CloudMassFraction));
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitBondedImpact::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  craterkit::bridge::printProperties(
      os, indent, "ProjectileShape", this->ProjectileShape, "Diameter", this->Diameter,
      "CylinderLengthRatio", this->CylinderLengthRatio, "ThicknessRatio", this->ThicknessRatio,
      "PlateWidthRatio", this->PlateWidthRatio, "ProjectileDensity", this->ProjectileDensity,
      "PlateDensity", this->PlateDensity, "ImpactSpeed", this->ImpactSpeed, "ImpactAngle",
      this->ImpactAngle, "Spacing", this->Spacing, "ParticleCount", this->ParticleCount, "Epsilon",
      this->Epsilon, "Kappa", this->Kappa, "CutoffRatio", this->CutoffRatio, "ReferenceSigma",
      this->ReferenceSigma, "Temperature", this->Temperature, "Seed", this->Seed, "TimeStep",
      this->TimeStep, "EndTime", this->EndTime, "OutputInterval", this->OutputInterval,
      "CloudMassFraction", this->CloudMassFraction, "Dissipation", this->Dissipation,
      "ShockViscosityLinear", this->ShockViscosityLinear, "ShockViscosityQuadratic",
      this->ShockViscosityQuadratic, "ShockViscosityThreshold", this->ShockViscosityThreshold,
      "CheckpointInterval", this->CheckpointInterval, "ResumeFromCheckpoint",
      this->ResumeFromCheckpoint, "KeptStates", this->KeptStates, "CheckpointFile",
      this->CheckpointFile);
}
