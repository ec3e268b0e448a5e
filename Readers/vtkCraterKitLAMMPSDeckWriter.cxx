#include "vtkCraterKitLAMMPSDeckWriter.h"

#include "CraterKitDemSetup.h"
#include "vtkCraterKitSolverBridge.h"

#include "dem/LammpsDeck.h"

#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPointSet.h>

#include <string>
#include <vector>

vtkStandardNewMacro(vtkCraterKitLAMMPSDeckWriter);

vtkCraterKitLAMMPSDeckWriter::vtkCraterKitLAMMPSDeckWriter() = default;

vtkCraterKitLAMMPSDeckWriter::~vtkCraterKitLAMMPSDeckWriter() { this->SetFileName(nullptr); }

int vtkCraterKitLAMMPSDeckWriter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkCraterKitLAMMPSDeckWriter::WriteData() {
  using namespace craterkit;
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  const bool ok = bridge::run(this, [&] {
    if (!this->FileName || !*this->FileName)
      throw InputError("FileName: no deck directory given");
    vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
    // The DEM problem exactly as DEMIntegrator would set it up from this input.
    const DemProblem problem = setUpDem(bridge::fromPolyData(input), bridge::demSetupOf(this, fd));
    LammpsDeckParams deck;
    deck.dem = problem.params;
    deck.startTime = bridge::fieldScalar(fd, "Time", 0.0);
    // DEMIntegrator's output times after the state's own, counted from it (LAMMPS starts at 0).
    for (double t : bridge::outputTimes(deck.startTime, this->EndTime, this->OutputInterval))
      if (t > deck.startTime)
        deck.outputTimes.push_back(t - deck.startTime);
    if (deck.outputTimes.empty())
      throw InputError("EndTime " + std::to_string(this->EndTime) +
                       " s is not after the input's Time " + std::to_string(deck.startTime) +
                       " s (or OutputInterval is not positive): the deck would have no output");
    writeLammpsDeck(this->FileName, problem.particles, deck);
  });
  if (!ok)
    this->SetErrorCode(1);
}

void vtkCraterKitLAMMPSDeckWriter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  // One "Name: value" line per property, with the XML names (the proxy test compares them).
  const auto line = [&](const char* name, const auto& v) {
    os << indent << name << ": " << v << "\n";
  };
  const auto vec = [&](const char* name, const double* v) {
    os << indent << name << ": " << v[0] << " " << v[1] << " " << v[2] << "\n";
  };
  line("FileName", this->FileName ? this->FileName : "(none)");
#define CK_LINE(name) line(#name, this->name)
  CK_LINE(ContactLaw), CK_LINE(NormalStiffness), CK_LINE(TangentialStiffness);
  CK_LINE(NormalRestitution), CK_LINE(TangentialRestitution), CK_LINE(StaticFriction);
  CK_LINE(RollingFriction), CK_LINE(TwistingFriction), CK_LINE(ShapeParameter);
  CK_LINE(Cohesion), CK_LINE(YoungsModulus), CK_LINE(PoissonRatio), CK_LINE(MaxExpectedSpeed);
  CK_LINE(MaxOverlap), CK_LINE(Container), CK_LINE(ContainerRadius), vec("BoxSize", this->BoxSize);
  CK_LINE(GravityModel), vec("SurfaceGravity", this->SurfaceGravity), CK_LINE(PointMassGM);
  vec("PointMassCentre", this->PointMassCentre), CK_LINE(TimeStep), CK_LINE(StepsPerCollision);
  CK_LINE(EndTime), CK_LINE(OutputInterval), CK_LINE(AddImpactor), CK_LINE(ImpactorRadius);
  CK_LINE(ImpactorDensity), CK_LINE(ImpactSpeed), CK_LINE(ImpactAngle);
#undef CK_LINE
}
