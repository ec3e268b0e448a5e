#include "vtkCraterKitGranularBed.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "bed/GranularBed.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkCraterKitGranularBed);

vtkCraterKitGranularBed::vtkCraterKitGranularBed() { this->SetNumberOfInputPorts(0); }

int vtkCraterKitGranularBed::RequestData(vtkInformation*, vtkInformationVector**,
                                         vtkInformationVector* outputVector) {
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  using namespace craterkit;

  GranularBedParams p;
  p.packing = enums::kPacking.toSolver(this->Packing);
  p.container.type = enums::kBedContainer.toSolver(this->Container);
  p.container.bowlRadius = this->ContainerRadius;
  p.container.boxSize = {this->BoxSize[0], this->BoxSize[1], this->BoxSize[2]};
  p.container.surfaceHeight = this->SurfaceHeight;
  p.sizes.type = enums::kSizeDistribution.toSolver(this->SizeDistribution);
  p.sizes.radius = this->ParticleRadius;
  p.sizes.minRadius = this->MinRadius;
  p.sizes.maxRadius = this->MaxRadius;
  p.sizes.exponent = this->PowerLawExponent;
  p.packingFraction = this->PackingFraction;
  p.particleDensity = this->ParticleDensity;
  p.material = this->Material;
  p.seed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->RandomSeed));
  p.maxParticles = this->MaxParticles;
  p.settle = this->Settle != 0;
  p.settlingGravity = this->SettlingGravity;
  p.settlingFriction = this->SettlingFriction;
  p.stageMaxExpectedSpeed = this->DEMMaxExpectedSpeed;
  p.stageMaxOverlap = this->DEMMaxOverlap;
  p.stageNormalStiffness = this->DEMNormalStiffness;

  ParticleSet bed;
  GranularBedReport report;
  if (!bridge::run(this, [&] { bed = generateGranularBed(p, &report, bridge::progressOf(this)); }))
    return 0;

  bridge::toPolyData(bed, output);
  vtkFieldData* fd = output->GetFieldData();
  bridge::addField(fd, "Time", 0.0);
  bridge::addField(fd, "Packing", GranularBedParams::packingName(p.packing));
  bridge::addField(fd, "ContainerType", Container::typeName(p.container.type));
  bridge::addField(fd, "ContainerRadius", p.container.bowlRadius);
  bridge::addField(fd, "BoxSize", p.container.boxSize.data(), 3);
  bridge::addField(fd, "SurfaceHeight", p.container.surfaceHeight);
  bridge::addField(fd, "SizeDistribution", SizeDistribution::typeName(p.sizes.type));
  bridge::addField(fd, "MinRadius", p.sizes.smallest());
  bridge::addField(fd, "MaxRadius", p.sizes.largest());
  bridge::addField(fd, "PowerLawExponent", p.sizes.exponent);
  bridge::addField(fd, "ParticleDensity", p.particleDensity);
  bridge::addField(fd, "RandomSeed", static_cast<double>(this->RandomSeed));
  bridge::addField(fd, "BulkPackingFraction", report.bulkPackingFraction);
  bridge::addField(fd, "TopHeight", report.topHeight);
  bridge::addField(fd, "NumberOfParticles", static_cast<double>(report.particles));
  bridge::addField(fd, "CoordinationNumber", report.coordinationNumber);
  if (p.settles()) {
    bridge::addField(fd, "Settled", report.settled ? 1.0 : 0.0);
    bridge::addField(fd, "SettlingTime", report.settlingTime);
    bridge::addField(fd, "SettlingSteps", static_cast<double>(report.settlingSteps));
    bridge::addField(fd, "SettlingGravity", p.settlingGravity);
    bridge::addField(fd, "RestNormalStiffness", report.stageStiffness);
    bridge::addField(fd, "RestTimeStep", report.stageTimeStep);
    bridge::addField(fd, "AtRest", report.atRest ? 1.0 : 0.0);
    bridge::addField(fd, "RestSpeed", report.restSpeed);
    if (!report.settled)
      vtkWarningMacro(<< "the bed was still moving after " << report.settlingTime
                      << " s of settling; its packing may be looser than a settled one");
    else if (!report.atRest)
      vtkWarningMacro(<< "the bed had not come to rest in the DEM stage's contact law after "
                      << report.restSteps << " steps: its fastest grain moved at "
                      << report.restSpeed << " sqrt(g r)");
  }
  return 1;
}

void vtkCraterKitGranularBed::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  // One "Name: value" line per property, with the XML property names: the proxy test
  // compares these C++ defaults with the XML defaults.
  os << indent << "Packing: " << this->Packing << "\n";
  os << indent << "Container: " << this->Container << "\n";
  os << indent << "ContainerRadius: " << this->ContainerRadius << "\n";
  os << indent << "BoxSize: " << this->BoxSize[0] << " " << this->BoxSize[1] << " "
     << this->BoxSize[2] << "\n";
  os << indent << "SurfaceHeight: " << this->SurfaceHeight << "\n";
  os << indent << "SizeDistribution: " << this->SizeDistribution << "\n";
  os << indent << "ParticleRadius: " << this->ParticleRadius << "\n";
  os << indent << "MinRadius: " << this->MinRadius << "\n";
  os << indent << "MaxRadius: " << this->MaxRadius << "\n";
  os << indent << "PowerLawExponent: " << this->PowerLawExponent << "\n";
  os << indent << "PackingFraction: " << this->PackingFraction << "\n";
  os << indent << "ParticleDensity: " << this->ParticleDensity << "\n";
  os << indent << "Material: " << this->Material << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "MaxParticles: " << this->MaxParticles << "\n";
  os << indent << "Settle: " << this->Settle << "\n";
  os << indent << "SettlingGravity: " << this->SettlingGravity << "\n";
  os << indent << "SettlingFriction: " << this->SettlingFriction << "\n";
  os << indent << "DEMMaxExpectedSpeed: " << this->DEMMaxExpectedSpeed << "\n";
  os << indent << "DEMMaxOverlap: " << this->DEMMaxOverlap << "\n";
  os << indent << "DEMNormalStiffness: " << this->DEMNormalStiffness << "\n";
}
