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
#include <fstream>
#include <vector>

vtkStandardNewMacro(vtkCraterKitSPHImpact);

vtkCraterKitSPHImpact::vtkCraterKitSPHImpact() { this->SetNumberOfInputPorts(0); }
vtkCraterKitSPHImpact::~vtkCraterKitSPHImpact() = default;

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

craterkit::SphImpactSetup vtkCraterKitSPHImpact::Setup() const {
  using craterkit::SphImpactSetup;
  SphImpactSetup setup;
  setup.materialDirectory =
      craterkit::materialDirectory(this->MaterialDirectory, CRATERKIT_MATERIALS_DIR);
  setup.impactorMaterial = this->ImpactorMaterial;
  setup.impactorMass = this->ImpactorMass;
  setup.impactorRadius = this->ImpactorRadius;
  setup.impactSpeed = this->ImpactSpeed;
  setup.impactAngle = this->ImpactAngle;
  setup.targetMaterial = this->TargetMaterial;
  setup.targetShape = craterkit::enums::kTargetShape.toSolver(this->TargetShape);
  setup.targetRadius = this->TargetRadius;
  setup.coarsening = this->TargetCoarsening;
  setup.targetPorosity = this->TargetPorosity;
  setup.frictionAngle = this->FrictionAngle;
  setup.cohesion = this->Cohesion;
  setup.surfaceGravity = this->SurfaceGravity;
  setup.particlesAcrossImpactor = this->ParticlesAcrossImpactor;
  setup.container = this->TargetContainer;
  return setup;
}

void vtkCraterKitSPHImpact::BuildRun() {
  using namespace craterkit;
  checkImpactTimes(this->EndTime, this->OutputInterval, this->MinTimeStep);
  SphImpactProblem problem = buildImpact(this->Setup());
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
  b::setVertices(output, std::vector<double>(s.x.begin(), s.x.begin() + 3 * n));
  vtkPointData* pd = output->GetPointData();
  for (const SphImpactArray& a : impactArrays(solver, nOut))
    pd->AddArray(b::doubleArray(a.name.c_str(), a.components, a.values));
  pd->AddArray(
      b::intArray("Material", std::vector<int>(s.material.begin(), s.material.begin() + n)));
  std::vector<std::int64_t> ids(nOut);
  for (std::size_t i = 0; i < ids.size(); ++i)
    ids[i] = static_cast<std::int64_t>(i);
  pd->AddArray(b::idArray("Id", ids));
  pd->SetActiveScalars("Pressure");

  vtkFieldData* fd = output->GetFieldData();
  for (const SphImpactField& f :
       impactFields(solver, this->Setup(), this->Spacing, this->ContainerParticles)) {
    if (f.isText)
      b::addField(fd, f.name.c_str(), f.text);
    else
      b::addField(fd, f.name.c_str(), f.values.data(), static_cast<int>(f.values.size()));
  }
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
