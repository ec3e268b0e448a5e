#include "vtkCraterKitImpactHandoff.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "common/Container.h"
#include "handoff/Handoff.h"

#include <vtkAlgorithm.h>
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
    const SphSnapshot s = b::sphSnapshotOf<SphSnapshot>(sphIn);
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
  b::addFields(fd, reportedFigures(r));

  vtkPolyData* surface = vtkPolyData::GetData(outputVector, 1);
  b::setTriangles(surface, r.surfacePoints, r.triangles);
  b::addField(surface->GetFieldData(), "AlphaRadius", r.alphaRadius);
  return 1;
}

void vtkCraterKitImpactHandoff::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  craterkit::bridge::printProperties(
      os, indent, "EjectaSpeedLimit", this->EjectaSpeedLimit, "Alpha", this->Alpha, "MinNeighbours",
      this->MinNeighbours, "HandoffTime", this->HandoffTime, "EjectaDensity", this->EjectaDensity,
      "EjectaParticles", this->EjectaParticles, "CurtainAsParticles", this->CurtainAsParticles,
      "DropEjectaLandingOutside", this->DropEjectaLandingOutside);
}
