#include "vtkCraterKitHardDiskCrater.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "analysis/CraterProfile.h"
#include "edmd/HardDiskCrater.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTypeInt64Array.h>

#include <algorithm>
#include <cmath>
#include <numeric>

vtkStandardNewMacro(vtkCraterKitHardDiskCrater);

vtkCraterKitHardDiskCrater::vtkCraterKitHardDiskCrater() {
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
}

vtkCraterKitHardDiskCrater::~vtkCraterKitHardDiskCrater() = default;

namespace {
using craterkit::HardDiskCraterParams;

// Model coordinates (x, y up) to the output's x-z plane.
void AddPoint(vtkPoints* points, double x, double y) { points->InsertNextPoint(x, 0.0, y); }
} // namespace

int vtkCraterKitHardDiskCrater::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                   vtkInformationVector* outputVector) {
  const std::vector<double> times =
      craterkit::hardDiskFrameTimes(this->FrameInterval, this->EndTime);
  const double range[2] = {times.front(), times.back()};
  for (int port = 0; port < 3; ++port) {
    vtkInformation* outInfo = outputVector->GetInformationObject(port);
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
                 static_cast<int>(times.size()));
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkCraterKitHardDiskCrater::RequestData(vtkInformation*, vtkInformationVector**,
                                            vtkInformationVector* outputVector) {
  using namespace craterkit;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  double t = 0.0;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());

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
  const HardDisks& d = run.system().disks();
  const double frameTime = run.frameTime(run.currentFrame());

  // Output 0: disks (the model's x, y up in the output's x-z plane).
  vtkPolyData* disks = vtkPolyData::GetData(outputVector, 0);
  {
    std::vector<double> xyz(3 * d.size()), velocity(3 * d.size()), density(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      xyz[3 * i] = d.x[i], xyz[3 * i + 1] = 0.0, xyz[3 * i + 2] = d.y[i];
      velocity[3 * i] = d.vx[i], velocity[3 * i + 1] = 0.0, velocity[3 * i + 2] = d.vy[i];
      density[i] = d.mass[i] / (M_PI * d.radius[i] * d.radius[i]);
    }
    std::vector<int> tracer(d.size(), 0);
    for (std::uint32_t k : run.tracers())
      tracer[k] = 1;
    const std::vector<char>& touched = run.system().disturbed();
    bridge::setVertices(disks, xyz);
    vtkPointData* pd = disks->GetPointData();
    pd->AddArray(bridge::doubleArray("Velocity", 3, velocity));
    pd->AddArray(bridge::doubleArray("Radius", 1, d.radius));
    pd->AddArray(bridge::doubleArray("Mass", 1, d.mass));
    pd->AddArray(bridge::doubleArray("Density", 1, density));
    pd->AddArray(bridge::intArray("Material", d.material));
    pd->AddArray(bridge::intArray("IsTracer", tracer));
    pd->AddArray(bridge::intArray("Disturbed", std::vector<int>(touched.begin(), touched.end())));
    pd->AddArray(bridge::idArray("Id", d.id));
    pd->SetActiveScalars("Radius");
  }

  // Output 1: tracer paths up to this frame.
  vtkPolyData* paths = vtkPolyData::GetData(outputVector, 1);
  {
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    auto lines = vtkSmartPointer<vtkCellArray>::New();
    auto time = vtkSmartPointer<vtkDoubleArray>::New();
    time->SetName("Time");
    auto ids = vtkSmartPointer<vtkTypeInt64Array>::New();
    ids->SetName("Id");
    for (std::size_t k = 0; k < run.tracers().size(); ++k) {
      const std::vector<double>& path = run.tracerPaths()[k];
      const vtkIdType count = static_cast<vtkIdType>(path.size() / 2);
      lines->InsertNextCell(count);
      for (vtkIdType f = 0; f < count; ++f) {
        lines->InsertCellPoint(points->GetNumberOfPoints());
        AddPoint(points, path[2 * f], path[2 * f + 1]);
        time->InsertNextValue(run.frameTime(static_cast<std::size_t>(f)));
      }
      ids->InsertNextValue(d.id[run.tracers()[k]]);
    }
    paths->SetPoints(points);
    paths->SetLines(lines);
    paths->GetPointData()->AddArray(time);
    paths->GetCellData()->AddArray(ids);
  }

  // Output 2: crater outline, and its depth and width.
  vtkPolyData* outline = vtkPolyData::GetData(outputVector, 2);
  double depth = 0.0, width = 0.0;
  {
    const double bin = 4.0 * std::max(run.params().diskRadius, run.params().maxDiskRadius);
    const std::vector<double> top = run.surfaceProfile(bin);
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    auto lines = vtkSmartPointer<vtkCellArray>::New();
    lines->InsertNextCell(static_cast<vtkIdType>(top.size()));
    for (std::size_t b = 0; b < top.size(); ++b) {
      lines->InsertCellPoint(static_cast<vtkIdType>(b));
      AddPoint(points, (b + 0.5) * bin, top[b]);
    }
    outline->SetPoints(points);
    outline->SetLines(lines);
    // The crater: more than one disk diameter below the original surface.
    const SectionCrater crater =
        measureSection(top, bin, run.impactX(), run.surfaceLevel(), 2.0 * run.params().diskRadius);
    depth = crater.depth;
    width = crater.width;
  }

  // Field data shared by the three outputs.
  auto fd = vtkSmartPointer<vtkFieldData>::New();
  const std::vector<HardDiskCraterRun::Ejection> ejections = run.ejections();
  const double meanAngle = HardDiskCraterRun::meanEjectionAngle(ejections);
  double px, py;
  run.system().momentum(px, py);
  const double momentum[3] = {px, 0.0, py};
  const double impact[3] = {run.impactX(), 0.0, run.surfaceLevel()};
  bridge::addField(fd, "Time", frameTime);
  bridge::addField(fd, "Frame", static_cast<double>(run.currentFrame()));
  bridge::addField(fd, "PairCollisions", static_cast<double>(run.system().pairCollisions()));
  bridge::addField(fd, "WallCollisions", static_cast<double>(run.system().wallCollisions()));
  bridge::addField(fd, "KineticEnergy", run.system().kineticEnergy());
  bridge::addField(fd, "TotalMomentum", momentum, 3);
  bridge::addField(fd, "ShockFrontRadius", run.shockFront().back());
  bridge::addField(fd, "ImpactPoint", impact, 3);
  bridge::addField(fd, "SurfaceHeight", run.surfaceLevel());
  const double box[3] = {run.system().params().width, 0.0, run.system().params().height};
  bridge::addField(fd, "BoxSize", box, 3);
  bridge::addField(fd, "EjectedDisks", static_cast<double>(ejections.size()));
  bridge::addField(fd, "MeanEjectionAngle", meanAngle);
  bridge::addField(fd, "CraterDepth", depth);
  bridge::addField(fd, "CraterWidth", width);
  // Per ejected disk (first upward crossing of the original surface, exact on its path), and
  // the shock front at every frame so far: for plots without re-running.
  auto series = [&](const char* name, std::size_t count, auto&& value) {
    auto a = vtkSmartPointer<vtkDoubleArray>::New();
    a->SetName(name);
    a->SetNumberOfTuples(static_cast<vtkIdType>(count));
    for (std::size_t k = 0; k < count; ++k)
      a->SetValue(static_cast<vtkIdType>(k), value(k));
    fd->AddArray(a);
  };
  series("EjectionAngle", ejections.size(), [&](std::size_t k) { return ejections[k].angleDeg; });
  series("EjectionDistance", ejections.size(),
         [&](std::size_t k) { return ejections[k].distance; });
  series("EjectionSpeed", ejections.size(), [&](std::size_t k) { return ejections[k].speed; });
  series("EjectionTime", ejections.size(), [&](std::size_t k) { return ejections[k].time; });
  series("ShockFrontHistory", run.shockFront().size(),
         [&](std::size_t k) { return run.shockFront()[k]; });
  bridge::addField(fd, "GroundDisks",
                   static_cast<double>(std::count(d.material.begin(), d.material.end(), 0)));
  for (int port = 0; port < 3; ++port) {
    vtkPolyData* out = vtkPolyData::GetData(outputVector, port);
    out->GetFieldData()->ShallowCopy(fd);
    out->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
  return 1;
}

void vtkCraterKitHardDiskCrater::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Preset: " << this->Preset << "\n";
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "GroundDepth: " << this->GroundDepth << "\n";
  os << indent << "Headroom: " << this->Headroom << "\n";
  os << indent << "DiskRadius: " << this->DiskRadius << "\n";
  os << indent << "MaxDiskRadius: " << this->MaxDiskRadius << "\n";
  os << indent << "AreaFraction: " << this->AreaFraction << "\n";
  os << indent << "GroundDensity: " << this->GroundDensity << "\n";
  os << indent << "ImpactorType: " << this->ImpactorType << "\n";
  os << indent << "ImpactorRadius: " << this->ImpactorRadius << "\n";
  os << indent << "DensityRatio: " << this->DensityRatio << "\n";
  os << indent << "ImpactSpeed: " << this->ImpactSpeed << "\n";
  os << indent << "ImpactAngle: " << this->ImpactAngle << "\n";
  os << indent << "Restitution: " << this->Restitution << "\n";
  os << indent << "Gravity: " << this->Gravity << "\n";
  os << indent << "FrameInterval: " << this->FrameInterval << "\n";
  os << indent << "EndTime: " << this->EndTime << "\n";
  os << indent << "TracerFraction: " << this->TracerFraction << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
}
