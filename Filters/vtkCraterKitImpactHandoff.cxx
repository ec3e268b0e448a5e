#include "vtkCraterKitImpactHandoff.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "handoff/Handoff.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <chrono>
#include <cmath>

vtkStandardNewMacro(vtkCraterKitImpactHandoff);

vtkCraterKitImpactHandoff::vtkCraterKitImpactHandoff() {
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

int vtkCraterKitImpactHandoff::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

int vtkCraterKitImpactHandoff::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                  vtkInformationVector* outputVector) {
  // The hand-off is one state: no time steps downstream (the DEM run starts from it).
  for (int port = 0; port < 2; ++port) {
    vtkInformation* out = outputVector->GetInformationObject(port);
    out->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    out->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  return 1;
}

int vtkCraterKitImpactHandoff::RequestUpdateExtent(vtkInformation*,
                                                   vtkInformationVector** inputVector,
                                                   vtkInformationVector*) {
  vtkInformation* sph = inputVector[0]->GetInformationObject(0);
  double t = this->HandoffTime;
  if (t < 0.0 && sph->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())) {
    const int n = sph->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    t = sph->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[n - 1];
  }
  if (t >= 0.0)
    sph->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), t);
  vtkInformation* bed = inputVector[1]->GetInformationObject(0);
  if (bed->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
    bed->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(),
             bed->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[0]);
  return 1;
}

int vtkCraterKitImpactHandoff::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector) {
  using namespace craterkit;
  namespace b = craterkit::bridge;
  vtkPointSet* sphIn = vtkPointSet::GetData(inputVector[0], 0);
  vtkPointSet* bedIn = vtkPointSet::GetData(inputVector[1], 0);
  vtkPolyData* out = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* surface = vtkPolyData::GetData(outputVector, 1);
  if (!sphIn || !bedIn) {
    vtkErrorMacro(<< "ImpactHandoff needs the SPH state on input 0 and a bed on input 1");
    return 0;
  }
  HandoffResult r;
  ParticleSet bed;
  const bool ok = b::run(this, [&] {
    const vtkIdType n = sphIn->GetNumberOfPoints();
    vtkDataArray* vel = sphIn->GetPointData()->GetArray("Velocity");
    vtkDataArray* mass = sphIn->GetPointData()->GetArray("Mass");
    vtkDataArray* h = sphIn->GetPointData()->GetArray("SmoothingLength");
    if (n == 0)
      throw InputError("the SPH input (port 0) has no particles");
    if (!vel || vel->GetNumberOfComponents() != 3 || !mass)
      throw InputError(
          "the SPH input (port 0) needs point arrays Velocity (3 components) and Mass");
    SphSnapshot s;
    s.x.resize(3 * n), s.v.resize(3 * n), s.mass.resize(n), s.h.assign(n, 0.0);
    for (vtkIdType i = 0; i < n; ++i) {
      sphIn->GetPoint(i, &s.x[3 * i]);
      vel->GetTuple(i, &s.v[3 * i]);
      s.mass[i] = mass->GetComponent(i, 0);
      if (h)
        s.h[i] = h->GetComponent(i, 0);
    }
    bed = b::fromPolyData(bedIn);
    TargetRegion region;
    vtkFieldData* fd = sphIn->GetFieldData();
    const std::string shape = b::fieldString(fd, "TargetShape");
    region.radius = b::fieldScalar(fd, "TargetRadius", 0.0);
    region.surfaceHeight = b::fieldScalar(fd, "SurfaceHeight", 0.0);
    if (shape == "Hemisphere" && region.radius > 0.0)
      region.shape = TargetRegion::Shape::Hemisphere;
    else if (shape == "HalfSpace" && region.radius > 0.0)
      region.shape = TargetRegion::Shape::HalfSpace;
    else
      vtkWarningMacro(
          << "the SPH input does not say where its target was (field data TargetShape, "
             "TargetRadius): every bed particle outside the alpha shape is carved away");
    HandoffParams p;
    p.ejectaSpeedLimit = this->EjectaSpeedLimit;
    p.alphaRadius = this->Alpha;
    p.minNeighbours = this->MinNeighbours;
    p.ejectaDensity = this->EjectaDensity;
    // Dropped ejecta leave only the curtain to become particles; it lands on the bed, so it
    // comes as grains of the bed's size (SPH-particle-sized ones would set the DEM step).
    const enums::EjectaHandling ejecta = enums::kEjectaParticles.toSolver(this->EjectaParticles);
    p.groupEjecta = ejecta.group;
    p.dropEjecta = ejecta.drop;
    p.curtainAsParticles = this->CurtainAsParticles != 0;
    // Ejecta stay inside the bed's container (GranularBed's field data); with
    // DropEjectaLandingOutside, what comes down outside its footprint leaves the domain.
    vtkFieldData* bfd = bedIn->GetFieldData();
    const std::string container = b::fieldString(bfd, "ContainerType");
    const bool dropOutside = this->DropEjectaLandingOutside != 0;
    if (container == "Bowl") {
      const double R = b::fieldScalar(bfd, "ContainerRadius", 0.0);
      if (R > 0.0) {
        p.allowed = [R](const double* x, double rad) { // the bowl and the cylinder above its rim
          const double horizontal = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          return horizontal + rad <= R &&
                 (x[2] > 0.0 || std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) + rad <= R);
        };
        if (dropOutside)
          p.landsInside = [R](double x, double y) { return x * x + y * y <= R * R; };
      }
    } else if (container == "Box") {
      vtkDataArray* box = bfd->GetArray("BoxSize");
      if (box && box->GetNumberOfComponents() == 3) {
        double L[3];
        box->GetTuple(0, L);
        p.allowed = [L](const double* x, double rad) {
          return std::abs(x[0]) + rad <= 0.5 * L[0] && std::abs(x[1]) + rad <= 0.5 * L[1] &&
                 x[2] - rad >= -L[2];
        };
        if (dropOutside)
          p.landsInside = [L](double x, double y) {
            return std::abs(x) <= 0.5 * L[0] && std::abs(y) <= 0.5 * L[1];
          };
      }
    }
    vtkDataArray* g = sphIn->GetFieldData()->GetArray("Gravity");
    if (g && g->GetNumberOfComponents() == 3)
      p.gravity = std::max(0.0, -g->GetComponent(0, 2)); // along -z
    else if (p.landsInside)
      vtkWarningMacro(
          << "the SPH input has no Gravity field: with DropEjectaLandingOutside, material moving "
             "up never comes down and leaves the domain");
    r = handoff(s, bed, region, p);
  });
  if (!ok)
    return 0;
  for (const std::string& w : r.warnings)
    vtkWarningMacro(<< w);

  b::toPolyData(r.particles, out);
  out->GetPointData()->AddArray(b::intArray("Origin", r.origin));
  vtkFieldData* fd = out->GetFieldData();
  fd->ShallowCopy(bedIn->GetFieldData()); // the container, for DEMIntegrator
  vtkFieldData* sfd = sphIn->GetFieldData();
  b::addField(fd, "Time", b::fieldScalar(sfd, "Time", 0.0));
  if (vtkDataArray* g = sfd->GetArray("Gravity"))
    if (g->GetNumberOfComponents() == 3) {
      double gv[3];
      g->GetTuple(0, gv);
      b::addField(fd, "Gravity", gv, 3);
    }
  auto totals = [&](const char* prefix, const HandoffTotals& t) {
    b::addField(fd, (std::string(prefix) + "Mass").c_str(), t.mass);
    b::addField(fd, (std::string(prefix) + "Momentum").c_str(), t.momentum.data(), 3);
    b::addField(fd, (std::string(prefix) + "AngularMomentum").c_str(), t.angularMomentum.data(), 3);
  };
  totals("SPHCompact", r.sphCompact);
  totals("SPHEjecta", r.sphEjecta);
  totals("SPHCurtain", r.sphCurtain);
  totals("SPHEscaped", r.sphEscaped);
  b::addField(fd, "EscapedCount", static_cast<double>(r.escapedCount));
  totals("SPHLoneDropped", r.sphLoneDropped);
  b::addField(fd, "LoneDroppedCount", static_cast<double>(r.loneDropped));
  totals("DEMMappedBeforeCorrection", r.demBefore);
  totals("DEMMapped", r.demMapped);
  totals("DEMEjecta", r.demEjecta);
  const double below = r.sphCompact.mass - r.sphCurtain.mass; // the compact mass the bed takes over
  b::addField(fd, "CompactMassRatio", below > 0.0 ? r.demMapped.mass / below : 0.0);
  b::addField(fd, "CurtainCount", static_cast<double>(r.curtainCount));
  b::addField(fd, "AlphaRadius", r.alphaRadius);
  b::addField(fd, "AlphaShapeVolume", r.shapeVolume);
  b::addField(fd, "BedRemoved", static_cast<double>(r.bedRemoved));
  b::addField(fd, "BedMapped", static_cast<double>(r.bedMapped));
  b::addField(fd, "EjectaCount", static_cast<double>(r.ejectaCount));
  b::addField(fd, "EjectaShrunk", static_cast<double>(r.ejectaShrunk));
  b::addField(fd, "BedEvicted", static_cast<double>(r.bedEvicted));
  const double times[6] = {r.seconds.split, r.seconds.alphaShape, r.seconds.carve,
                           r.seconds.map,   r.seconds.correct,    r.seconds.ejecta};
  b::addField(fd, "StepSeconds", times, 6); // split, alpha shape, carve, map, correct, ejecta

  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  const vtkIdType nv = static_cast<vtkIdType>(r.surfacePoints.size() / 3);
  points->SetNumberOfPoints(nv);
  for (vtkIdType i = 0; i < nv; ++i)
    points->SetPoint(i, &r.surfacePoints[3 * i]);
  auto tris = vtkSmartPointer<vtkCellArray>::New();
  for (std::size_t k = 0; k + 2 < r.triangles.size(); k += 3) {
    const vtkIdType ids[3] = {static_cast<vtkIdType>(r.triangles[k]),
                              static_cast<vtkIdType>(r.triangles[k + 1]),
                              static_cast<vtkIdType>(r.triangles[k + 2])};
    tris->InsertNextCell(3, ids);
  }
  surface->SetPoints(points);
  surface->SetPolys(tris);
  b::addField(surface->GetFieldData(), "AlphaRadius", r.alphaRadius);
  return 1;
}

void vtkCraterKitImpactHandoff::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EjectaSpeedLimit: " << this->EjectaSpeedLimit << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "MinNeighbours: " << this->MinNeighbours << "\n";
  os << indent << "HandoffTime: " << this->HandoffTime << "\n";
  os << indent << "EjectaDensity: " << this->EjectaDensity << "\n";
  os << indent << "EjectaParticles: " << this->EjectaParticles << "\n";
  os << indent << "CurtainAsParticles: " << this->CurtainAsParticles << "\n";
  os << indent << "DropEjectaLandingOutside: " << this->DropEjectaLandingOutside << "\n";
}
