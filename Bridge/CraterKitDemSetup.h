// The DEM run a proxy with DEMIntegrator's properties describes (craterkit::DemSetup,
// Solvers/dem/DemSetup.h), read from its getters and the input's field data (the container
// GranularBed recorded, the surface height). DEMIntegrator runs it; LAMMPSDeckWriter writes it
// as a LAMMPS deck, so that both stages start from the same contact law, walls, gravity,
// stiffness and step.
#pragma once

#include "CraterKitEnumTables.h"
#include "vtkCraterKitSolverBridge.h"

#include "dem/DemSetup.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace craterkit::bridge {

// PROXY has the getters of DEMIntegrator's contact, wall, gravity, step and impactor
// properties (Plugin/xml/DEMIntegrator.xml).
template <class Proxy> DemSetup demSetupOf(Proxy* p, vtkFieldData* fd) {
  DemSetup setup;
  ContactParams& c = setup.contact;
  c.normalModel = std::string(enums::kContactLaw.toSolver(p->GetContactLaw()));
  c.kT = p->GetTangentialStiffness();
  c.restitutionN = p->GetNormalRestitution();
  c.restitutionT = p->GetTangentialRestitution();
  c.muS = p->GetStaticFriction();
  c.muR = p->GetRollingFriction();
  c.muT = p->GetTwistingFriction();
  c.beta = p->GetShapeParameter();
  c.cohesion = p->GetCohesion();
  c.youngsModulus = p->GetYoungsModulus();
  c.poissonRatio = p->GetPoissonRatio();
  setup.normalStiffness = p->GetNormalStiffness();
  setup.timeStep = p->GetTimeStep();
  setup.stepsPerCollision = p->GetStepsPerCollision();
  setup.maxExpectedSpeed = p->GetMaxExpectedSpeed();
  setup.maxOverlap = p->GetMaxOverlap();
  Gravity& g = setup.gravity;
  g.type = enums::kGravityModel.toSolver(p->GetGravityModel());
  std::copy(p->GetSurfaceGravity(), p->GetSurfaceGravity() + 3, g.vector.begin());
  g.GM = p->GetPointMassGM();
  std::copy(p->GetPointMassCentre(), p->GetPointMassCentre() + 3, g.centre.begin());
  setup.addImpactor = p->GetAddImpactor() != 0;
  setup.impactor = ImpactorParams{p->GetImpactorRadius(), p->GetImpactorDensity(),
                                  p->GetImpactSpeed(), p->GetImpactAngle()};
  setup.surfaceHeight = fieldScalar(fd, "SurfaceHeight", std::nan(""));

  Container& box = setup.container;
  box.bowlRadius = p->GetContainerRadius();
  const double* size = p->GetBoxSize();
  box.boxSize = {size[0], size[1], size[2]};
  const enums::DemContainer walls = enums::kDemContainer.toSolver(p->GetContainer());
  std::string type = walls == enums::DemContainer::Box    ? "Box"
                     : walls == enums::DemContainer::Bowl ? "Bowl"
                                                          : "";
  if (walls == enums::DemContainer::FromInput) {
    type = fieldString(fd, "ContainerType");
    box.bowlRadius = fieldScalar(fd, "ContainerRadius", p->GetContainerRadius());
    vtkDataArray* recorded = fd->GetArray("BoxSize");
    for (int k = 0; k < 3 && recorded && recorded->GetNumberOfComponents() == 3; ++k)
      box.boxSize[k] = recorded->GetComponent(0, k);
  }
  chooseWalls(setup, type, walls == enums::DemContainer::Cylinder);
  return setup;
}

} // namespace craterkit::bridge
