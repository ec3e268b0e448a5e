#include "vtkCraterKitDEMIntegrator.h"

#include "CraterKitDemSetup.h"
#include "vtkCraterKitSolverBridge.h"

#include "dem/DemRun.h"
#include "dem/DemSetup.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

vtkStandardNewMacro(vtkCraterKitDEMIntegrator);

vtkCraterKitDEMIntegrator::vtkCraterKitDEMIntegrator() = default;
vtkCraterKitDEMIntegrator::~vtkCraterKitDEMIntegrator() = default;

int vtkCraterKitDEMIntegrator::RequestInformation(vtkInformation*,
                                                  vtkInformationVector** inputVector,
                                                  vtkInformationVector* outputVector) {
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // The start time comes from the input's data if it carries one; otherwise 0.
  double start = 0.0;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
    start = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[0];
  craterkit::bridge::setTimeSteps(
      outInfo, craterkit::bridge::outputTimes(start, this->EndTime, this->OutputInterval));
  return 1;
}

void vtkCraterKitDEMIntegrator::BuildRun(vtkPolyData* input) {
  using namespace craterkit;
  vtkFieldData* fd = input->GetFieldData();
  const DemSetup setup = bridge::demSetupOf(this, fd);
  const DemProblem problem = setUpDem(bridge::fromPolyData(input), setup);
  // The run rebuilds its initial state from the input when it needs it again, instead of
  // holding a copy (a shallow copy shares the input's arrays; a new input rebuilds the run).
  vtkSmartPointer<vtkPolyData> held = vtkSmartPointer<vtkPolyData>::New();
  held->ShallowCopy(input);
  this->Run = std::make_unique<DemRun>(
      problem.particles,
      [held, setup] { return setUpDem(bridge::fromPolyData(held), setup).particles; },
      problem.params, bridge::fieldScalar(fd, "Time", 0.0),
      static_cast<std::size_t>(std::max(0, this->KeptStates)));
  bridge::resumeIfAsked(*this->Run, this->ResumeFromCheckpoint != 0, this->CheckpointFile);
  this->WarningsShown = 0;
}

int vtkCraterKitDEMIntegrator::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector) {
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;

  if (!bridge::ensureRun(this, this->Run, this->RunBuildTime,
                         input->GetMTime() > this->RunBuildTime, [&] { this->BuildRun(input); }))
    return 0;
  const double t = bridge::requestedTime(outInfo, this->Run->time());
  const std::string checkpoint = this->CheckpointFile;
  const bool ok = bridge::run(this, [&] {
    this->Run->advanceTo(t, bridge::progressOf(this), checkpoint, this->CheckpointInterval);
  });
  if (!ok) {
    this->Run.reset(); // a failed or aborted run restarts cleanly on the next request
    return 0;
  }

  const DemSolver& solver = this->Run->solver();
  const std::vector<std::string>& warnings = solver.warnings();
  for (; this->WarningsShown < warnings.size(); ++this->WarningsShown)
    vtkWarningMacro(<< warnings[this->WarningsShown]);

  bridge::toPolyData(solver.particles(), output);
  vtkFieldData* fd = output->GetFieldData();
  fd->ShallowCopy(input->GetFieldData());
  bridge::addFields(fd, demFields(*this->Run, this->SurfaceGravity));
  // The pipeline time is the requested one (the state is the first step at or after it;
  // field data "Time" holds the exact simulated time).
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitDEMIntegrator::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  // One "Name: value" line per property, with the XML property names: the proxy test
  // compares these C++ defaults with the XML defaults.
  const auto line = [&](const char* name, const auto& v) {
    os << indent << name << ": " << v << "\n";
  };
  const auto vec = [&](const char* name, const double* v) {
    os << indent << name << ": " << v[0] << " " << v[1] << " " << v[2] << "\n";
  };
#define CK_LINE(name) line(#name, this->name)
  CK_LINE(ContactLaw), CK_LINE(NormalStiffness), CK_LINE(TangentialStiffness);
  CK_LINE(NormalRestitution), CK_LINE(TangentialRestitution), CK_LINE(StaticFriction);
  CK_LINE(RollingFriction), CK_LINE(TwistingFriction), CK_LINE(ShapeParameter);
  CK_LINE(Cohesion), CK_LINE(YoungsModulus), CK_LINE(PoissonRatio), CK_LINE(MaxExpectedSpeed);
  CK_LINE(MaxOverlap), CK_LINE(Container), CK_LINE(ContainerRadius), vec("BoxSize", this->BoxSize);
  CK_LINE(GravityModel), vec("SurfaceGravity", this->SurfaceGravity), CK_LINE(PointMassGM);
  vec("PointMassCentre", this->PointMassCentre), CK_LINE(TimeStep), CK_LINE(StepsPerCollision);
  CK_LINE(EndTime), CK_LINE(OutputInterval), CK_LINE(AddImpactor), CK_LINE(ImpactorRadius);
  CK_LINE(ImpactorDensity), CK_LINE(ImpactSpeed), CK_LINE(ImpactAngle), CK_LINE(CheckpointFile);
  CK_LINE(CheckpointInterval), CK_LINE(ResumeFromCheckpoint), CK_LINE(KeptStates);
#undef CK_LINE
}
