#include "vtkCraterKitHardDiskCrater.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "edmd/HardDiskCrater.h"
#include "edmd/HardDiskReport.h"

#include <vtkCellData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkCraterKitHardDiskCrater);

vtkCraterKitHardDiskCrater::vtkCraterKitHardDiskCrater() {
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
}

vtkCraterKitHardDiskCrater::~vtkCraterKitHardDiskCrater() = default;

int vtkCraterKitHardDiskCrater::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                   vtkInformationVector* outputVector) {
  const std::vector<double> times =
      craterkit::hardDiskFrameTimes(this->FrameInterval, this->EndTime);
  for (int port = 0; port < 3; ++port)
    craterkit::bridge::setTimeSteps(outputVector->GetInformationObject(port), times);
  return 1;
}

int vtkCraterKitHardDiskCrater::RequestData(vtkInformation*, vtkInformationVector**,
                                            vtkInformationVector* outputVector) {
  using namespace craterkit;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const double t = craterkit::bridge::requestedTime(outInfo, 0.0);

  HardDiskCraterParams p;
  const bool ok = bridge::run(this, [&] {
    const std::string_view preset = enums::kHardDiskPreset.toSolver(this->Preset);
    if (!preset.empty())
      p = HardDiskCraterParams::preset(std::string(preset));
    else {
      p.width = this->Width;
      p.groundDepth = this->GroundDepth;
      p.headroom = this->Headroom;
      p.diskRadius = this->DiskRadius;
      p.maxDiskRadius = this->MaxDiskRadius;
      p.areaFraction = this->AreaFraction;
      p.groundDensity = this->GroundDensity;
      p.impactor = enums::kImpactorType.toSolver(this->ImpactorType);
      p.impactorRadius = this->ImpactorRadius;
      p.densityRatio = this->DensityRatio;
      p.impactSpeed = this->ImpactSpeed;
      p.impactAngle = this->ImpactAngle;
      p.restitution = this->Restitution;
      p.gravity = this->Gravity;
    }
    // Output controls apply to presets too.
    p.frameInterval = this->FrameInterval;
    p.endTime = this->EndTime;
    p.tracerFraction = this->TracerFraction;
    p.seed = static_cast<std::uint64_t>(this->RandomSeed);
    p.validate();

    const std::size_t frame =
        static_cast<std::size_t>(std::max(0.0, std::round(t / p.frameInterval)));
    // A new run when a property changed or an earlier frame is asked for (runs go forwards).
    if (!this->Run || this->GetMTime() > this->RunBuildTime || frame < this->Run->currentFrame()) {
      this->Run.reset();
      this->Run = std::make_unique<HardDiskCraterRun>(p, bridge::progressOf(this, 0.0, 0.2));
      this->RunBuildTime.Modified();
    }
    this->Run->advanceToFrame(std::min(frame, this->Run->frameCount() - 1),
                              bridge::progressOf(this, 0.2, 1.0));
  });
  if (!ok) {
    this->Run.reset();
    return 0;
  }

  const HardDiskCraterRun& run = *this->Run;
  namespace b = craterkit::bridge;
  // Output 0: disks (the model's x, y up in the output's x-z plane).
  vtkPolyData* disks = vtkPolyData::GetData(outputVector, 0);
  const HardDisks& d = run.system().disks();
  const HardDiskPoints points = hardDiskPoints(run);
  b::setVertices(disks, points.xyz);
  vtkPointData* pd = disks->GetPointData();
  pd->AddArray(b::doubleArray("Velocity", 3, points.velocity));
  pd->AddArray(b::doubleArray("Radius", 1, d.radius));
  pd->AddArray(b::doubleArray("Mass", 1, d.mass));
  pd->AddArray(b::doubleArray("Density", 1, points.density));
  pd->AddArray(b::intArray("Material", d.material));
  pd->AddArray(b::intArray("IsTracer", points.tracer));
  pd->AddArray(b::intArray("Disturbed", points.disturbed));
  pd->AddArray(b::idArray("Id", d.id));
  pd->SetActiveScalars("Radius");

  // Output 1: tracer paths up to this frame.
  vtkPolyData* paths = vtkPolyData::GetData(outputVector, 1);
  const HardDiskLines tracers = hardDiskTracerPaths(run);
  b::setPolyLines(paths, tracers.xyz, tracers.counts);
  paths->GetPointData()->AddArray(b::doubleArray("Time", 1, tracers.time));
  paths->GetCellData()->AddArray(b::idArray("Id", tracers.ids));

  // Output 2: crater outline. Field data shared by the three outputs.
  const HardDiskLines outline = hardDiskOutline(run);
  b::setPolyLines(vtkPolyData::GetData(outputVector, 2), outline.xyz, outline.counts);
  auto fd = vtkSmartPointer<vtkFieldData>::New();
  b::addFields(fd, hardDiskFields(run, outline.crater));
  for (int port = 0; port < 3; ++port) {
    vtkPolyData* out = vtkPolyData::GetData(outputVector, port);
    out->GetFieldData()->ShallowCopy(fd);
    out->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
  return 1;
}

void vtkCraterKitHardDiskCrater::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  craterkit::bridge::printProperties(
      os, indent, "Preset", this->Preset, "Width", this->Width, "GroundDepth", this->GroundDepth,
      "Headroom", this->Headroom, "DiskRadius", this->DiskRadius, "MaxDiskRadius",
      this->MaxDiskRadius, "AreaFraction", this->AreaFraction, "GroundDensity", this->GroundDensity,
      "ImpactorType", this->ImpactorType, "ImpactorRadius", this->ImpactorRadius, "DensityRatio",
      this->DensityRatio, "ImpactSpeed", this->ImpactSpeed, "ImpactAngle", this->ImpactAngle,
      "Restitution", this->Restitution, "Gravity", this->Gravity, "FrameInterval",
      this->FrameInterval, "EndTime", this->EndTime, "TracerFraction", this->TracerFraction,
      "RandomSeed", this->RandomSeed);
}
