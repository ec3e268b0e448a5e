#include "vtkCraterKitSPHImpact.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "sph/ImpactSetup.h"
#include "sph/SphRun.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <vector>

vtkStandardNewMacro(vtkCraterKitSPHImpact);

vtkCraterKitSPHImpact::vtkCraterKitSPHImpact() { this->SetNumberOfInputPorts(0); }
vtkCraterKitSPHImpact::~vtkCraterKitSPHImpact() = default;

namespace {
std::string DefaultMaterialDirectory() {
  if (const char* env = std::getenv("CRATERKIT_MATERIALS"))
    return env;
  return CRATERKIT_MATERIALS_DIR;
}
} // namespace

int vtkCraterKitSPHImpact::RequestInformation(vtkInformation*, vtkInformationVector**,
                                              vtkInformationVector* outputVector) {
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const std::vector<double> times =
      craterkit::bridge::outputTimes(0.0, this->EndTime, this->OutputInterval, 100000);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
               static_cast<int>(times.size()));
  const double range[2] = {times.front(), times.back()};
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

void vtkCraterKitSPHImpact::BuildRun() {
  using namespace craterkit;
  if (!(this->EndTime >= 0.0) || !std::isfinite(this->EndTime))
    throw InputError("EndTime must be a non-negative time in s");
  if (!(this->OutputInterval > 0.0))
    throw InputError("OutputInterval must be positive");
  if (!(this->MinTimeStep >= 0.0))
    throw InputError("MinTimeStep must not be negative");
  SphImpactSetup setup;
  setup.materialDirectory =
      this->MaterialDirectory.empty() ? DefaultMaterialDirectory() : this->MaterialDirectory;
  setup.impactorMaterial = this->ImpactorMaterial;
  setup.impactorMass = this->ImpactorMass;
  setup.impactorRadius = this->ImpactorRadius;
  setup.impactSpeed = this->ImpactSpeed;
  setup.impactAngle = this->ImpactAngle;
  setup.targetMaterial = this->TargetMaterial;
  setup.targetShape = enums::kTargetShape.toSolver(this->TargetShape);
  setup.targetRadius = this->TargetRadius;
  setup.coarsening = this->TargetCoarsening;
  setup.targetPorosity = this->TargetPorosity;
  setup.frictionAngle = this->FrictionAngle;
  setup.cohesion = this->Cohesion;
  setup.surfaceGravity = this->SurfaceGravity;
  setup.particlesAcrossImpactor = this->ParticlesAcrossImpactor;
  setup.container = this->TargetContainer;
  SphImpactProblem problem = buildImpact(setup);
  SphParams& p = problem.params;
  p.kernel = enums::kKernel.toSolver(this->Kernel);
  p.alpha = this->ArtificialViscosityAlpha;
  p.beta = this->ArtificialViscosityBeta;
  p.xsph = this->XSPH;
  p.courant = this->CourantNumber;
  p.minTimeStep = this->MinTimeStep;
  p.lateStageTime = this->LateStageTime;
  p.domainRadius = this->DomainRadius;
  p.lateStageSoundSpeed = this->LateStageSoundSpeed;
  this->Spacing = problem.spacing;
  this->ContainerParticles = problem.containerParticles;
  this->Run = std::make_unique<SphRun>(problem.state, p,
                                       static_cast<std::size_t>(std::max(0, this->KeptStates)));
  if (this->ResumeFromCheckpoint && !this->CheckpointFile.empty() &&
      std::ifstream(this->CheckpointFile).good())
    this->Run->resumeFrom(this->CheckpointFile);
}

int vtkCraterKitSPHImpact::RequestData(vtkInformation*, vtkInformationVector**,
                                       vtkInformationVector* outputVector) {
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;
  namespace b = craterkit::bridge;

  if (!this->Run || this->GetMTime() > this->RunBuildTime) {
    this->Run.reset();
    if (!b::run(this, [&] { this->BuildRun(); }))
      return 0;
    this->RunBuildTime.Modified();
  }
  double t = 0.0;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  t = std::max(0.0, std::min(t, this->EndTime));
  const bool ok = b::run(this, [&] {
    this->Run->advanceTo(t, b::progressOf(this), this->CheckpointFile, this->CheckpointInterval);
  });
  if (!ok) {
    this->Run.reset(); // a failed or aborted run restarts cleanly on the next request
    return 0;
  }

  const SphSolver& solver = this->Run->solver();
  const SphState& s = solver.state();
  // The container's particles are the last ones; like the DEM's walls they are not output.
  const std::size_t nOut = s.size() - this->ContainerParticles;
  const vtkIdType n = static_cast<vtkIdType>(nOut);
  auto head = [nOut](const std::vector<double>& v, std::size_t components) {
    return std::vector<double>(v.begin(),
                               v.begin() + static_cast<std::ptrdiff_t>(nOut * components));
  };
  b::setVertices(output, head(s.x, 3));

  vtkPointData* pd = output->GetPointData();
  pd->AddArray(b::doubleArray("Velocity", 3, head(s.v, 3)));
  pd->AddArray(b::doubleArray("Density", 1, head(s.rho, 1)));
  pd->AddArray(b::doubleArray("Mass", 1, head(s.mass, 1)));
  pd->AddArray(b::doubleArray("Pressure", 1, head(solver.pressure(), 1)));
  pd->AddArray(b::doubleArray("InternalEnergy", 1, head(s.u, 1)));
  pd->AddArray(b::doubleArray("Distention", 1, head(s.alpha, 1)));
  pd->AddArray(b::doubleArray("Damage", 1, head(s.damage, 1)));
  pd->AddArray(b::doubleArray("SmoothingLength", 1, head(s.h, 1)));
  pd->AddArray(b::doubleArray("SoundSpeed", 1, head(solver.soundSpeed(), 1)));
  // VTK's symmetric tensor order is XX YY ZZ XY YZ XZ; the solver stores XX YY ZZ XY XZ YZ.
  std::vector<double> stress(6 * nOut);
  for (vtkIdType i = 0; i < n; ++i) {
    const double* S = &s.S[6 * i];
    double* o = &stress[6 * i];
    o[0] = S[0], o[1] = S[1], o[2] = S[2], o[3] = S[3], o[4] = S[5], o[5] = S[4];
  }
  pd->AddArray(b::doubleArray("DeviatoricStress", 6, stress));
  pd->AddArray(
      b::intArray("Material", std::vector<int>(s.material.begin(), s.material.begin() + n)));
  std::vector<std::int64_t> ids(nOut);
  for (std::size_t i = 0; i < ids.size(); ++i)
    ids[i] = static_cast<std::int64_t>(i);
  pd->AddArray(b::idArray("Id", ids));
  pd->SetActiveScalars("Pressure");

  vtkFieldData* fd = output->GetFieldData();
  b::addField(fd, "Time", solver.time());
  b::addField(fd, "Step", static_cast<double>(solver.steps()));
  b::addField(fd, "TimeStep", solver.stableStep());
  const double g[3] = {0.0, 0.0, -this->SurfaceGravity};
  b::addField(fd, "Gravity", g, 3);
  double P[3], L[3];
  solver.totalMomentum(P);
  solver.totalAngularMomentum(L);
  b::addField(fd, "TotalMomentum", P, 3);
  b::addField(fd, "TotalAngularMomentum", L, 3);
  b::addField(fd, "KineticEnergy", solver.kineticEnergy());
  b::addField(fd, "InternalEnergyTotal", solver.internalEnergy());
  b::addField(fd, "GravitationalEnergy", solver.potentialEnergy());
  b::addField(fd, "TotalEnergy", solver.totalEnergy());
  b::addField(fd, "ParticleSpacing", this->Spacing);
  b::addField(fd, "SurfaceHeight", 0.0);
  b::addField(fd, "TargetRadius", this->TargetRadius);
  b::addField(fd, "TargetCoarsening", this->TargetCoarsening);
  b::addField(fd, "TargetContainer", this->TargetContainer ? 1.0 : 0.0);
  b::addField(fd, "ContainerParticles", static_cast<double>(this->ContainerParticles));
  b::addField(fd, "TargetShape", std::string(enums::kTargetShape.text(this->TargetShape)));
  b::addField(fd, "ImpactSpeed", this->ImpactSpeed);
  b::addField(fd, "ImpactAngle", this->ImpactAngle);
  b::addField(fd, "ImpactorMaterial", this->ImpactorMaterial);
  b::addField(fd, "ImpactorMass", this->ImpactorMass);
  b::addField(fd, "TargetMaterial", this->TargetMaterial);
  b::addField(fd, "FrictionAngle", this->FrictionAngle);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitSPHImpact::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaterialDirectory: " << this->MaterialDirectory << "\n";
  os << indent << "ImpactorMaterial: " << this->ImpactorMaterial << "\n";
  os << indent << "ImpactorMass: " << this->ImpactorMass << "\n";
  os << indent << "ImpactorRadius: " << this->ImpactorRadius << "\n";
  os << indent << "ImpactSpeed: " << this->ImpactSpeed << "\n";
  os << indent << "ImpactAngle: " << this->ImpactAngle << "\n";
  os << indent << "TargetMaterial: " << this->TargetMaterial << "\n";
  os << indent << "TargetShape: " << this->TargetShape << "\n";
  os << indent << "TargetRadius: " << this->TargetRadius << "\n";
  os << indent << "TargetCoarsening: " << this->TargetCoarsening << "\n";
  os << indent << "TargetPorosity: " << this->TargetPorosity << "\n";
  os << indent << "FrictionAngle: " << this->FrictionAngle << "\n";
  os << indent << "Cohesion: " << this->Cohesion << "\n";
  os << indent << "SurfaceGravity: " << this->SurfaceGravity << "\n";
  os << indent << "ParticlesAcrossImpactor: " << this->ParticlesAcrossImpactor << "\n";
  os << indent << "TargetContainer: " << this->TargetContainer << "\n";
  os << indent << "EndTime: " << this->EndTime << "\n";
  os << indent << "OutputInterval: " << this->OutputInterval << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
  os << indent << "ArtificialViscosityAlpha: " << this->ArtificialViscosityAlpha << "\n";
  os << indent << "ArtificialViscosityBeta: " << this->ArtificialViscosityBeta << "\n";
  os << indent << "XSPH: " << this->XSPH << "\n";
  os << indent << "CourantNumber: " << this->CourantNumber << "\n";
  os << indent << "MinTimeStep: " << this->MinTimeStep << "\n";
  os << indent << "LateStageTime: " << this->LateStageTime << "\n";
  os << indent << "DomainRadius: " << this->DomainRadius << "\n";
  os << indent << "LateStageSoundSpeed: " << this->LateStageSoundSpeed << "\n";
  os << indent << "CheckpointFile: " << this->CheckpointFile << "\n";
  os << indent << "CheckpointInterval: " << this->CheckpointInterval << "\n";
  os << indent << "ResumeFromCheckpoint: " << this->ResumeFromCheckpoint << "\n";
  os << indent << "KeptStates: " << this->KeptStates << "\n";
}
