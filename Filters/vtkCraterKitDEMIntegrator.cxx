#include "vtkCraterKitDEMIntegrator.h"

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "dem/DemRun.h"
#include "dem/Impactor.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
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
  const std::vector<double> times =
      craterkit::bridge::outputTimes(start, this->EndTime, this->OutputInterval);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
               static_cast<int>(times.size()));
  const double range[2] = {times.front(), times.back()};
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

void vtkCraterKitDEMIntegrator::BuildRun(vtkPolyData* input) {
  using namespace craterkit;
  vtkFieldData* fd = input->GetFieldData();
  ParticleSet particles = bridge::fromPolyData(input);
  const double start = bridge::fieldScalar(fd, "Time", 0.0);

  double zmin = VTK_DOUBLE_MAX, top = -VTK_DOUBLE_MAX, rmin = VTK_DOUBLE_MAX,
         rhoMin = VTK_DOUBLE_MAX;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    zmin = std::min(zmin, particles.position[3 * i + 2] - particles.radius[i]);
    top = std::max(top, particles.position[3 * i + 2] + particles.radius[i]);
    rmin = std::min(rmin, particles.radius[i]);
    rhoMin = std::min(rhoMin, particles.density[i]);
  }
  double vmax = this->MaxExpectedSpeed;
  if (this->AddImpactor) {
    ImpactorParams imp;
    imp.radius = this->ImpactorRadius;
    imp.density = this->ImpactorDensity;
    imp.speed = this->ImpactSpeed;
    imp.angle = this->ImpactAngle;
    imp.target[2] = bridge::fieldScalar(fd, "SurfaceHeight", top);
    addImpactor(particles, imp);
    vmax = std::max(vmax, this->ImpactSpeed);
    rmin = std::min(rmin, this->ImpactorRadius);
  }

  DemParams p;
  ContactParams& c = p.contact;
  c.normalModel = std::string(enums::kContactLaw.toSolver(this->ContactLaw));
  c.kT = this->TangentialStiffness;
  c.restitutionN = this->NormalRestitution;
  c.restitutionT = this->TangentialRestitution;
  c.muS = this->StaticFriction;
  c.muR = this->RollingFriction;
  c.muT = this->TwistingFriction;
  c.beta = this->ShapeParameter;
  c.cohesion = this->Cohesion;
  c.youngsModulus = this->YoungsModulus;
  c.poissonRatio = this->PoissonRatio;
  p.overlapWarning = this->MaxOverlap;

  Gravity& g = p.gravity;
  g.type = enums::kGravityModel.toSolver(this->GravityModel);
  std::copy(this->SurfaceGravity, this->SurfaceGravity + 3, g.vector.begin());
  g.GM = this->PointMassGM;
  std::copy(this->PointMassCentre, this->PointMassCentre + 3, g.centre.begin());
  double gmag = 0.0;
  if (g.type == Gravity::Type::Uniform)
    gmag = std::sqrt(g.vector[0] * g.vector[0] + g.vector[1] * g.vector[1] +
                     g.vector[2] * g.vector[2]);
  else if (g.type == Gravity::Type::PointMass) {
    const double d = std::hypot(g.centre[0], g.centre[1], g.centre[2] - top);
    gmag = d > 0.0 ? g.GM / (d * d) : 0.0;
  }

  // Stiffness and time step: given, or proposed from the largest expected speed, the
  // lithostatic load and the allowed overlap (Schwartz et al. 2012, PHYSICS.md §1.6).
  const StiffnessProposal proposal =
      proposeStiffness(rmin, rhoMin, vmax, this->MaxOverlap, gmag, std::max(top - zmin, rmin),
                       this->StepsPerCollision);
  c.kN = this->NormalStiffness > 0.0 ? this->NormalStiffness : proposal.kN;
  if (this->TimeStep > 0.0)
    p.dt = this->TimeStep;
  else {
    const double mmin = rhoMin * 4.0 / 3.0 * M_PI * rmin * rmin * rmin;
    p.dt = M_PI * std::sqrt(0.5 * mmin / c.kN) / this->StepsPerCollision;
  }

  craterkit::Container container;
  const enums::DemContainer walls = enums::kDemContainer.toSolver(this->Container);
  switch (walls) {
  case enums::DemContainer::FromInput: {
    const std::string type = bridge::fieldString(fd, "ContainerType");
    if (type == "Box" || type == "Bowl") {
      container.type =
          type == "Box" ? craterkit::Container::Type::Box : craterkit::Container::Type::Bowl;
      container.bowlRadius = bridge::fieldScalar(fd, "ContainerRadius", this->ContainerRadius);
      vtkDataArray* box = fd->GetArray("BoxSize");
      for (int k = 0; k < 3; ++k)
        container.boxSize[k] =
            box && box->GetNumberOfComponents() == 3 ? box->GetComponent(0, k) : this->BoxSize[k];
      p.walls = containerWalls(container);
    }
    break;
  }
  case enums::DemContainer::Box:
  case enums::DemContainer::Bowl:
    container.type = walls == enums::DemContainer::Box ? craterkit::Container::Type::Box
                                                       : craterkit::Container::Type::Bowl;
    container.bowlRadius = this->ContainerRadius;
    container.boxSize = {this->BoxSize[0], this->BoxSize[1], this->BoxSize[2]};
    p.walls = containerWalls(container);
    break;
  case enums::DemContainer::Cylinder:
    p.walls.push_back(Wall::cylinder({0, 0, 0}, {0, 0, 1}, this->ContainerRadius));
    p.walls.push_back(Wall::plane({0, 0, -this->BoxSize[2]}, {0, 0, 1}));
    break;
  default:
    break;
  }

  this->Run = std::make_unique<DemRun>(particles, p, start,
                                       static_cast<std::size_t>(std::max(0, this->KeptStates)));
  if (this->ResumeFromCheckpoint && !this->CheckpointFile.empty() &&
      std::ifstream(this->CheckpointFile).good())
    this->Run->resumeFrom(this->CheckpointFile);
  this->WarningsShown = 0;
}

int vtkCraterKitDEMIntegrator::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector) {
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using namespace craterkit;

  if (!this->Run || this->GetMTime() > this->RunBuildTime ||
      input->GetMTime() > this->RunBuildTime) {
    this->Run.reset();
    if (!bridge::run(this, [&] { this->BuildRun(input); }))
      return 0;
    this->RunBuildTime.Modified();
  }
  double t = this->Run->time();
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
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
  const DemDiagnostics d = solver.diagnostics();
  const double time = this->Run->time();
  bridge::addField(fd, "Time", time);
  bridge::addField(fd, "Step", static_cast<double>(d.step));
  bridge::addField(fd, "TimeStep", solver.params().dt);
  bridge::addField(fd, "NormalStiffness", solver.params().contact.kN);
  bridge::addField(fd, "KineticEnergy", d.kineticEnergy);
  bridge::addField(fd, "RotationalEnergy", d.rotationalEnergy);
  bridge::addField(fd, "ElasticEnergy", d.elasticEnergy);
  bridge::addField(fd, "GravitationalEnergy", d.gravitationalEnergy);
  bridge::addField(fd, "TotalMomentum", d.momentum.data(), 3);
  bridge::addField(fd, "TotalAngularMomentum", d.angularMomentum.data(), 3);
  bridge::addField(fd, "MaxOverlap", d.maxOverlap);
  bridge::addField(fd, "Contacts", static_cast<double>(d.contacts));
  bridge::addField(fd, "OverlapWarningSteps", static_cast<double>(solver.overlapWarnings()));
  const double g[3] = {this->SurfaceGravity[0], this->SurfaceGravity[1], this->SurfaceGravity[2]};
  bridge::addField(fd, "Gravity", g, 3);
  // The pipeline time is the requested one (the state is the first step at or after it;
  // field data "Time" holds the exact simulated time).
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  return 1;
}

void vtkCraterKitDEMIntegrator::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ContactLaw: " << this->ContactLaw << "\n";
  os << indent << "NormalStiffness: " << this->NormalStiffness << "\n";
  os << indent << "TangentialStiffness: " << this->TangentialStiffness << "\n";
  os << indent << "NormalRestitution: " << this->NormalRestitution << "\n";
  os << indent << "TangentialRestitution: " << this->TangentialRestitution << "\n";
  os << indent << "StaticFriction: " << this->StaticFriction << "\n";
  os << indent << "RollingFriction: " << this->RollingFriction << "\n";
  os << indent << "TwistingFriction: " << this->TwistingFriction << "\n";
  os << indent << "ShapeParameter: " << this->ShapeParameter << "\n";
  os << indent << "Cohesion: " << this->Cohesion << "\n";
  os << indent << "YoungsModulus: " << this->YoungsModulus << "\n";
  os << indent << "PoissonRatio: " << this->PoissonRatio << "\n";
  os << indent << "MaxExpectedSpeed: " << this->MaxExpectedSpeed << "\n";
  os << indent << "MaxOverlap: " << this->MaxOverlap << "\n";
  os << indent << "Container: " << this->Container << "\n";
  os << indent << "ContainerRadius: " << this->ContainerRadius << "\n";
  os << indent << "BoxSize: " << this->BoxSize[0] << " " << this->BoxSize[1] << " "
     << this->BoxSize[2] << "\n";
  os << indent << "GravityModel: " << this->GravityModel << "\n";
  os << indent << "SurfaceGravity: " << this->SurfaceGravity[0] << " " << this->SurfaceGravity[1]
     << " " << this->SurfaceGravity[2] << "\n";
  os << indent << "PointMassGM: " << this->PointMassGM << "\n";
  os << indent << "PointMassCentre: " << this->PointMassCentre[0] << " " << this->PointMassCentre[1]
     << " " << this->PointMassCentre[2] << "\n";
  os << indent << "TimeStep: " << this->TimeStep << "\n";
  os << indent << "StepsPerCollision: " << this->StepsPerCollision << "\n";
  os << indent << "EndTime: " << this->EndTime << "\n";
  os << indent << "OutputInterval: " << this->OutputInterval << "\n";
  os << indent << "AddImpactor: " << this->AddImpactor << "\n";
  os << indent << "ImpactorRadius: " << this->ImpactorRadius << "\n";
  os << indent << "ImpactorDensity: " << this->ImpactorDensity << "\n";
  os << indent << "ImpactSpeed: " << this->ImpactSpeed << "\n";
  os << indent << "ImpactAngle: " << this->ImpactAngle << "\n";
  os << indent << "CheckpointFile: " << this->CheckpointFile << "\n";
  os << indent << "CheckpointInterval: " << this->CheckpointInterval << "\n";
  os << indent << "ResumeFromCheckpoint: " << this->ResumeFromCheckpoint << "\n";
  os << indent << "KeptStates: " << this->KeptStates << "\n";
}
