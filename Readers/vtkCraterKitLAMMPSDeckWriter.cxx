#include "vtkCraterKitLAMMPSDeckWriter.h"

#include "CraterKitDemSetup.h"
#include "vtkCraterKitSolverBridge.h"

#include "bonded/BondedLammpsDeck.h"
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
    const double start = bridge::fieldScalar(fd, "Time", 0.0);
    // DEMIntegrator's output times after the state's own, counted from it (LAMMPS starts at 0).
    std::vector<double> times;
    for (double t : bridge::outputTimes(start, this->EndTime, this->OutputInterval))
      if (t > start)
        times.push_back(t - start);
    if (times.empty())
      throw InputError("EndTime " + std::to_string(this->EndTime) +
                       " s is not after the input's Time " + std::to_string(start) +
                       " s (or OutputInterval is not positive): the deck would have no output");
    if (fd && fd->GetArray("Kappa")) // a BondedImpact state: the bonded model's deck
      return this->WriteBonded(input, start, times);
    // The DEM problem exactly as DEMIntegrator would set it up from this input.
    const DemProblem problem = setUpDem(bridge::fromPolyData(input), bridge::demSetupOf(this, fd));
    LammpsDeckParams deck;
    deck.dem = problem.params;
    deck.startTime = start;
    deck.outputTimes = times;
    writeLammpsDeck(this->FileName, problem.particles, deck);
  });
  if (!ok)
    this->SetErrorCode(1);
}

// The bonded model (BondedImpact): the law and step from the field data, the bonds re-formed as
// at set-up, which only the first time step still has (the arrays do not say which broke).
void vtkCraterKitLAMMPSDeckWriter::WriteBonded(vtkPointSet* input, double start,
                                               const std::vector<double>& times) {
  using namespace craterkit;
  vtkFieldData* fd = input->GetFieldData();
  const double step = bridge::fieldScalar(fd, "Step", -1.0);
  if (step != 0.0)
    throw InputError("a bonded state can be written only at its first time step (Step 0, before "
                     "any bond broke): its point arrays do not say which bonds broke; got Step " +
                     std::to_string(step));
  ws2017::Law law;
  law.sigma = bridge::fieldScalar(fd, "Sigma", 0.0);
  law.epsilon = bridge::fieldScalar(fd, "Epsilon", 0.0);
  law.kappa = bridge::fieldScalar(fd, "Kappa", 0.0);
  law.rCut = bridge::fieldScalar(fd, "CutoffRadius", 0.0);
  BondedDeckParams deck;
  deck.bondStyle = this->HarmonicBonds ? BondedDeckParams::BondStyle::Harmonic
                                       : BondedDeckParams::BondStyle::PullOnly;
  deck.timeStep = bridge::fieldScalar(fd, "TimeStep", 0.0);
  deck.startTime = start;
  deck.outputTimes = times;
  writeBondedLammpsDeck(this->FileName, bondedSetUpState(bridge::fromPolyData(input), law), {},
                        deck);
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
  CK_LINE(ImpactorDensity), CK_LINE(ImpactSpeed), CK_LINE(ImpactAngle), CK_LINE(HarmonicBonds);
#undef CK_LINE
}
