#include "vtkCraterKitSPHImpact.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "common/Error.h"
#include "sph/ImpactSetup.h"
#include "sph/SphRun.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

vtkStandardNewMacro(vtkCraterKitSPHImpact);

namespace {
// The material folder that comes with the plugin, used when neither the MaterialDirectory
// property nor CRATERKIT_MATERIALS names one: share/craterkit/materials of an installed plugin,
// found relative to this library (CRATERKIT_MATERIALS_RELATIVE, Filters/CMakeLists.txt), else
// the link "materials" beside the plugin of a build tree (to the source tree's data/materials).
// Empty when there is neither.
std::string pluginMaterialDirectory() {
  namespace fs = std::filesystem;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&pluginMaterialDirectory), &info) == 0 || !info.dli_fname)
    return "";
  const fs::path here = fs::path(info.dli_fname).parent_path();
  for (const fs::path& candidate : {here / CRATERKIT_MATERIALS_RELATIVE, here / "materials"}) {
    std::error_code ec;
    const fs::path found = fs::canonical(candidate, ec);
    if (!ec && fs::is_directory(found, ec))
      return found.string();
  }
  return "";
}
} // namespace

vtkCraterKitSPHImpact::vtkCraterKitSPHImpact() { this->SetNumberOfInputPorts(0); }
vtkCraterKitSPHImpact::~vtkCraterKitSPHImpact() = default;

int vtkCraterKitSPHImpact::RequestInformation(vtkInformation*, vtkInformationVector**,
                                              vtkInformationVector* outputVector) {
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  craterkit::bridge::setTimeSteps(
      outInfo, craterkit::bridge::outputTimes(0.0, this->EndTime, this->OutputInterval, 100000));
  return 1;
}

craterkit::SphImpactSetup vtkCraterKitSPHImpact::Setup() const {
  using craterkit::SphImpactSetup;
  SphImpactSetup setup;
  setup.materialDirectory =
      craterkit::materialDirectory(this->MaterialDirectory, pluginMaterialDirectory());
  if (setup.materialDirectory.empty())
    throw craterkit::InputError(
        "no material folder: set MaterialDirectory or the environment variable "
        "CRATERKIT_MATERIALS (the plugin's own share/craterkit/materials was not found)");
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
  p.lateStageStopMaterial = this->StopImpactorAtLateStage ? kImpactorMaterial : -1;
  p.domainRadius = this->DomainRadius;
  p.lateStageSoundSpeed = this->LateStageSoundSpeed;
  p.lateStageInitialSoundSpeed = this->LateStageInitialSoundSpeed;
  p.lateStageSoundSpeedExponent = this->LateStageSoundSpeedExponent;
  p.lateStagePoissonRatio = this->LateStagePoissonRatio;
  p.blockStepLevels = this->BlockStepLevels;
  this->Spacing = problem.spacing;
  this->ContainerParticles = problem.containerParticles;
  this->Run = std::make_unique<SphRun>(problem.state, p,
                                       static_cast<std::size_t>(std::max(0, this->KeptStates)));
  craterkit::bridge::resumeIfAsked(*this->Run, this->ResumeFromCheckpoint != 0,
                                   this->CheckpointFile);
  // A resume from an old checkpoint, without a checksum, warns.
  for (const std::string& w : this->Run->warnings())
    vtkWarningMacro(<< w);
}

int vtkCraterKitSPHImpact::RequestData(vtkInformation*, vtkInformationVector**,
                                       vtkInformationVector* outputVector) {
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;
  namespace b = craterkit::bridge;

  if (!b::ensureRun(this, this->Run, this->RunBuildTime, false, [&] { this->BuildRun(); }))
    return 0;
  double t = b::requestedTime(outInfo, 0.0);
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
  b::addFields(fd, impactFields(solver, this->Setup(), this->Spacing, this->ContainerParticles));
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitSPHImpact::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  craterkit::bridge::printProperties(
      os, indent, "MaterialDirectory", this->MaterialDirectory, "ImpactorMaterial",
      this->ImpactorMaterial, "ImpactorMass", this->ImpactorMass, "ImpactorRadius",
      this->ImpactorRadius, "ImpactSpeed", this->ImpactSpeed, "ImpactAngle", this->ImpactAngle,
      "TargetMaterial", this->TargetMaterial, "TargetShape", this->TargetShape, "TargetRadius",
      this->TargetRadius, "TargetCoarsening", this->TargetCoarsening, "TargetPorosity",
      this->TargetPorosity, "FrictionAngle", this->FrictionAngle, "Cohesion", this->Cohesion,
      "SurfaceGravity", this->SurfaceGravity, "ParticlesAcrossImpactor",
      this->ParticlesAcrossImpactor, "TargetContainer", this->TargetContainer, "EndTime",
      this->EndTime, "OutputInterval", this->OutputInterval, "Kernel", this->Kernel,
      "ArtificialViscosityAlpha", this->ArtificialViscosityAlpha, "ArtificialViscosityBeta",
      this->ArtificialViscosityBeta, "XSPH", this->XSPH, "CourantNumber", this->CourantNumber,
      "MinTimeStep", this->MinTimeStep, "LateStageTime", this->LateStageTime,
      "StopImpactorAtLateStage", this->StopImpactorAtLateStage, "DomainRadius", this->DomainRadius,
      "LateStageSoundSpeed", this->LateStageSoundSpeed, "LateStageInitialSoundSpeed",
      this->LateStageInitialSoundSpeed, "LateStageSoundSpeedExponent",
      this->LateStageSoundSpeedExponent, "LateStagePoissonRatio", this->LateStagePoissonRatio,
      "BlockStepLevels", this->BlockStepLevels, "CheckpointFile", this->CheckpointFile,
      "CheckpointInterval", this->CheckpointInterval, "ResumeFromCheckpoint",
      this->ResumeFromCheckpoint, "KeptStates", this->KeptStates);
}
