#include "vtkCraterKitImpactHandoff.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "common/Container.h"
#include "handoff/Handoff.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <string>

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

namespace {
// The SPH state: positions, Velocity, Mass, optional SmoothingLength.
craterkit::SphSnapshot sphOf(vtkPointSet* in) {
  const vtkIdType n = in->GetNumberOfPoints();
  vtkDataArray* vel = in->GetPointData()->GetArray("Velocity");
  vtkDataArray* mass = in->GetPointData()->GetArray("Mass");
  vtkDataArray* h = in->GetPointData()->GetArray("SmoothingLength");
  if (n == 0)
    throw craterkit::InputError("the SPH input (port 0) has no particles");
  if (!vel || vel->GetNumberOfComponents() != 3 || !mass)
    throw craterkit::InputError(
        "the SPH input (port 0) needs point arrays Velocity (3 components) and Mass");
  craterkit::SphSnapshot s;
  s.x.resize(3 * n), s.v.resize(3 * n), s.mass.resize(n), s.h.assign(n, 0.0);
  for (vtkIdType i = 0; i < n; ++i) {
    in->GetPoint(i, &s.x[3 * i]);
    vel->GetTuple(i, &s.v[3 * i]);
    s.mass[i] = mass->GetComponent(i, 0);
    s.h[i] = h ? h->GetComponent(i, 0) : 0.0;
  }
  return s;
}
} // namespace

int vtkCraterKitImpactHandoff::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector) {
  using namespace craterkit;
  namespace b = craterkit::bridge;
  vtkPointSet* sphIn = vtkPointSet::GetData(inputVector[0], 0);
  vtkPointSet* bedIn = vtkPointSet::GetData(inputVector[1], 0);
  if (!sphIn || !bedIn) {
    vtkErrorMacro(<< "ImpactHandoff needs the SPH state on input 0 and a bed on input 1");
    return 0;
  }
  vtkFieldData* sfd = sphIn->GetFieldData();
  vtkFieldData* bfd = bedIn->GetFieldData();
  vtkDataArray* g = sfd->GetArray("Gravity");
  g = g && g->GetNumberOfComponents() == 3 ? g : nullptr;
  HandoffResult r;
  const bool ok = b::run(this, [&] {
    const SphSnapshot s = sphOf(sphIn);
    const ParticleSet bed = b::fromPolyData(bedIn);
    TargetRegion region;
    const std::string shape = b::fieldString(sfd, "TargetShape");
    region.radius = b::fieldScalar(sfd, "TargetRadius", 0.0);
    region.surfaceHeight = b::fieldScalar(sfd, "SurfaceHeight", 0.0);
    if ((shape == "Hemisphere" || shape == "HalfSpace") && region.radius > 0.0)
      region.shape =
          shape == "Hemisphere" ? TargetRegion::Shape::Hemisphere : TargetRegion::Shape::HalfSpace;
    else
      vtkWarningMacro(<< "the SPH input does not say where its target was (field data "
                         "TargetShape, TargetRadius): every bed particle outside the alpha "
                         "shape is carved away");
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
    // Ejecta stay inside the bed's container (GranularBed's field data), if it names one.
    Container c;
    const std::string type = b::fieldString(bfd, "ContainerType");
    c.bowlRadius = b::fieldScalar(bfd, "ContainerRadius", 0.0);
    vtkDataArray* box = bfd->GetArray("BoxSize");
    const bool hasBox = type == "Box" && box && box->GetNumberOfComponents() == 3;
    if (hasBox)
      c.type = Container::Type::Box, box->GetTuple(0, c.boxSize.data());
    if (hasBox || (type == "Bowl" && c.bowlRadius > 0.0))
      confineToContainer(p, c, this->DropEjectaLandingOutside != 0);
    if (g)
      p.gravity = std::max(0.0, -g->GetComponent(0, 2)); // along -z
    else if (p.landsInside)
      vtkWarningMacro(<< "the SPH input has no Gravity field: with DropEjectaLandingOutside, "
                         "material moving up never comes down and leaves the domain");
    r = handoff(s, bed, region, p);
  });
  if (!ok)
    return 0;
  for (const std::string& w : r.warnings)
    vtkWarningMacro(<< w);

  vtkPolyData* out = vtkPolyData::GetData(outputVector, 0);
  b::toPolyData(r.particles, out);
  out->GetPointData()->AddArray(b::intArray("Origin", r.origin));
  vtkFieldData* fd = out->GetFieldData();
  fd->ShallowCopy(bfd); // the container, for DEMIntegrator
  b::addField(fd, "Time", b::fieldScalar(sfd, "Time", 0.0));
  if (g)
    b::addField(fd, "Gravity", g->GetTuple3(0), 3);
  for (const HandoffFigure& f : reportedFigures(r))
    b::addField(fd, f.name.c_str(), f.values.data(), static_cast<int>(f.values.size()));

  vtkPolyData* surface = vtkPolyData::GetData(outputVector, 1);
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(r.surfacePoints.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    points->SetPoint(i, &r.surfacePoints[3 * i]);
  auto tris = vtkSmartPointer<vtkCellArray>::New();
  for (std::size_t k = 0; k + 2 < r.triangles.size(); k += 3)
    tris->InsertNextCell({r.triangles[k], r.triangles[k + 1], r.triangles[k + 2]});
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
