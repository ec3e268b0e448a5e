#include "vtkCraterKitHardDiskCrater.h"

#include "vtkCraterKitSolverBridge.h"

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

vtkSmartPointer<vtkIntArray> IntArray(const char* name, vtkIdType n) {
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(n);
  return a;
}

vtkSmartPointer<vtkDoubleArray> DoubleArray(const char* name, int components, vtkIdType n) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(n);
  return a;
}
} // namespace

int vtkCraterKitHardDiskCrater::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                   vtkInformationVector* outputVector) {
  std::vector<double> times{0.0};
  if (this->FrameInterval > 0.0 && this->EndTime > 0.0 &&
      std::isfinite(this->EndTime / this->FrameInterval)) {
    const long frames =
        static_cast<long>(std::floor(this->EndTime / this->FrameInterval * (1.0 + 1e-12)));
    for (long k = 1; k <= std::min(frames, 100000L); ++k)
      times.push_back(k * this->FrameInterval);
  }
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
    if (this->Preset != CUSTOM)
      p = HardDiskCraterParams::preset(HardDiskCraterParams::presetNames()[this->Preset - 1]);
    else {
      p.width = this->Width;
      p.groundDepth = this->GroundDepth;
      p.headroom = this->Headroom;
      p.diskRadius = this->DiskRadius;
      p.maxDiskRadius = this->MaxDiskRadius;
      p.areaFraction = this->AreaFraction;
      p.groundDensity = this->GroundDensity;
      p.impactor = this->ImpactorType == CLUMP ? HardDiskCraterParams::Impactor::Clump
                                               : HardDiskCraterParams::Impactor::Disk;
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
  const vtkIdType n = static_cast<vtkIdType>(d.size());
  const double frameTime = run.frameTime(run.currentFrame());

  // Output 0: disks.
  vtkPolyData* disks = vtkPolyData::GetData(outputVector, 0);
  {
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->Allocate(n);
    auto verts = vtkSmartPointer<vtkCellArray>::New();
    verts->AllocateExact(n, n);
    auto velocity = DoubleArray("Velocity", 3, n);
    auto radius = DoubleArray("Radius", 1, n);
    auto mass = DoubleArray("Mass", 1, n);
    auto density = DoubleArray("Density", 1, n);
    auto material = IntArray("Material", n);
    auto tracer = IntArray("IsTracer", n);
    auto disturbed = IntArray("Disturbed", n);
    auto ids = vtkSmartPointer<vtkTypeInt64Array>::New();
    ids->SetName("Id");
    ids->SetNumberOfTuples(n);
    tracer->FillValue(0);
    for (std::uint32_t k : run.tracers())
      tracer->SetValue(k, 1);
    for (vtkIdType i = 0; i < n; ++i) {
      AddPoint(points, d.x[i], d.y[i]);
      verts->InsertNextCell(1, &i);
      const double v[3] = {d.vx[i], 0.0, d.vy[i]};
      velocity->SetTuple(i, v);
      radius->SetValue(i, d.radius[i]);
      mass->SetValue(i, d.mass[i]);
      density->SetValue(i, d.mass[i] / (M_PI * d.radius[i] * d.radius[i]));
      material->SetValue(i, d.material[i]);
      disturbed->SetValue(i, run.system().disturbed()[i]);
      ids->SetValue(i, d.id[i]);
    }
    disks->SetPoints(points);
    disks->SetVerts(verts);
    vtkPointData* pd = disks->GetPointData();
    for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{
             velocity, radius, mass, density, material, tracer, disturbed, ids})
      pd->AddArray(a);
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
    // Depth below the original surface; width: the run of bins around the impact point
    // whose top is more than one disk diameter below the original surface.
    const std::size_t centre =
        std::min(top.size() - 1, static_cast<std::size_t>(run.impactX() / bin));
    const double surface = run.surfaceLevel(), drop = 2.0 * run.params().diskRadius;
    depth = std::max(0.0, surface - *std::min_element(top.begin(), top.end()));
    std::size_t lo = centre, hi = centre;
    if (top[centre] < surface - drop) {
      while (lo > 0 && top[lo - 1] < surface - drop)
        --lo;
      while (hi + 1 < top.size() && top[hi + 1] < surface - drop)
        ++hi;
      width = (hi - lo + 1) * bin;
    }
  }

  // Field data shared by the three outputs.
  auto fd = vtkSmartPointer<vtkFieldData>::New();
  const std::vector<HardDiskCraterRun::Ejection> ejections = run.ejections();
  double meanAngle = std::nan("");
  if (!ejections.empty()) {
    meanAngle = 0.0;
    for (const auto& e : ejections)
      meanAngle += e.angleDeg;
    meanAngle /= ejections.size();
  }
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
