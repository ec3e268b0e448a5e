/**
 * @class vtkCraterKitLAMMPSDeckWriter
 * @brief Writes a DEM state as a LAMMPS deck (data file and input deck) in a directory.
 *
 * Input: particles with the CraterKit arrays (a GranularBed, ImpactHandoff's Particles, a
 * DEMIntegrator time step; Radius and Mass or Density required, Velocity, AngularVelocity,
 * Material and Id optional) and the field data Time, ContainerType, ContainerRadius, BoxSize,
 * SurfaceHeight when present. The properties are DEMIntegrator's (the same names, defaults
 * and set-up through bridge::demSetupOf), so the deck holds the contact law, walls, gravity,
 * stiffness and step DEMIntegrator would run, and dumps at the output times DEMIntegrator
 * would give (from the input's Time to EndTime every OutputInterval). FileName is the deck's
 * directory (created): data.craterkit, in.craterkit; scripts/run-lammps runs it and the
 * LAMMPS dump reader reads its dump.craterkit. All deck logic lives in Solvers/dem/LammpsDeck.
 *
 * A BondedImpact state (field data Kappa) at its first time step gives the bonded model's deck
 * instead (Solvers/bonded/BondedLammpsDeck: lj/cut WCA repulsion, the pull-only bond as a table
 * or bond_style harmonic with HarmonicBonds, fix bond/break), with the law and step of its field
 * data and the output times as above; the DEM properties do not apply to it.
 */
#ifndef vtkCraterKitLAMMPSDeckWriter_h
#define vtkCraterKitLAMMPSDeckWriter_h

#include "CraterKitReadersModule.h"
#include <vtkWriter.h>

#include <vector>

class vtkPointSet;

class CRATERKITREADERS_EXPORT vtkCraterKitLAMMPSDeckWriter : public vtkWriter {
public:
  static vtkCraterKitLAMMPSDeckWriter* New();
  vtkTypeMacro(vtkCraterKitLAMMPSDeckWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  // The DEM properties, as DEMIntegrator's (vtkCraterKitDEMIntegrator.h, DEMIntegrator.xml).
  vtkSetClampMacro(ContactLaw, int, 0, 1);
  vtkGetMacro(ContactLaw, int);
  vtkSetMacro(NormalStiffness, double);
  vtkGetMacro(NormalStiffness, double);
  vtkSetMacro(TangentialStiffness, double);
  vtkGetMacro(TangentialStiffness, double);
  vtkSetMacro(NormalRestitution, double);
  vtkGetMacro(NormalRestitution, double);
  vtkSetMacro(TangentialRestitution, double);
  vtkGetMacro(TangentialRestitution, double);
  vtkSetMacro(StaticFriction, double);
  vtkGetMacro(StaticFriction, double);
  vtkSetMacro(RollingFriction, double);
  vtkGetMacro(RollingFriction, double);
  vtkSetMacro(TwistingFriction, double);
  vtkGetMacro(TwistingFriction, double);
  vtkSetMacro(ShapeParameter, double);
  vtkGetMacro(ShapeParameter, double);
  vtkSetMacro(Cohesion, double);
  vtkGetMacro(Cohesion, double);
  vtkSetMacro(YoungsModulus, double);
  vtkGetMacro(YoungsModulus, double);
  vtkSetMacro(PoissonRatio, double);
  vtkGetMacro(PoissonRatio, double);
  vtkSetMacro(MaxExpectedSpeed, double);
  vtkGetMacro(MaxExpectedSpeed, double);
  vtkSetMacro(MaxOverlap, double);
  vtkGetMacro(MaxOverlap, double);
  vtkSetClampMacro(Container, int, 0, 4);
  vtkGetMacro(Container, int);
  vtkSetMacro(ContainerRadius, double);
  vtkGetMacro(ContainerRadius, double);
  vtkSetVector3Macro(BoxSize, double);
  vtkGetVector3Macro(BoxSize, double);
  vtkSetClampMacro(GravityModel, int, 0, 2);
  vtkGetMacro(GravityModel, int);
  vtkSetVector3Macro(SurfaceGravity, double);
  vtkGetVector3Macro(SurfaceGravity, double);
  vtkSetMacro(PointMassGM, double);
  vtkGetMacro(PointMassGM, double);
  vtkSetVector3Macro(PointMassCentre, double);
  vtkGetVector3Macro(PointMassCentre, double);
  vtkSetMacro(TimeStep, double);
  vtkGetMacro(TimeStep, double);
  vtkSetMacro(StepsPerCollision, double);
  vtkGetMacro(StepsPerCollision, double);
  vtkSetMacro(EndTime, double);
  vtkGetMacro(EndTime, double);
  vtkSetMacro(OutputInterval, double);
  vtkGetMacro(OutputInterval, double);
  vtkSetMacro(AddImpactor, int);
  vtkGetMacro(AddImpactor, int);
  vtkSetMacro(ImpactorRadius, double);
  vtkGetMacro(ImpactorRadius, double);
  vtkSetMacro(ImpactorDensity, double);
  vtkGetMacro(ImpactorDensity, double);
  vtkSetMacro(ImpactSpeed, double);
  vtkGetMacro(ImpactSpeed, double);
  vtkSetMacro(ImpactAngle, double);
  vtkGetMacro(ImpactAngle, double);
  // Bonded decks: 1 = bond_style harmonic (also pushes compressed bonds), 0 = Eq. 4's pull-only
  // bond as a table (bonded/BondedLammpsDeck.h).
  vtkSetClampMacro(HarmonicBonds, int, 0, 1);
  vtkGetMacro(HarmonicBonds, int);

protected:
  vtkCraterKitLAMMPSDeckWriter();
  ~vtkCraterKitLAMMPSDeckWriter() override;
  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;
  int ContactLaw = 0;
  double NormalStiffness = 0.0;
  double TangentialStiffness = -1.0;
  double NormalRestitution = 0.55;
  double TangentialRestitution = 0.55;
  double StaticFriction = 0.6;
  double RollingFriction = 0.35;
  double TwistingFriction = 0.4375;
  double ShapeParameter = 0.5;
  double Cohesion = 0.0;
  double YoungsModulus = 1.0e8;
  double PoissonRatio = 0.25;
  double MaxExpectedSpeed = 1.0;
  double MaxOverlap = 0.01;
  int Container = 0;
  double ContainerRadius = 15.0;
  double BoxSize[3] = {10.0, 10.0, 5.0};
  int GravityModel = 1;
  double SurfaceGravity[3] = {0.0, 0.0, -1.5e-4};
  double PointMassGM = 30.0;
  double PointMassCentre[3] = {0.0, 0.0, -448.0};
  double TimeStep = 0.0;
  double StepsPerCollision = 30.0;
  double EndTime = 10.0;
  double OutputInterval = 1.0;
  int AddImpactor = 0;
  double ImpactorRadius = 0.5;
  double ImpactorDensity = 8900.0;
  double ImpactSpeed = 2.0;
  double ImpactAngle = 0.0;
  int HarmonicBonds = 0;

private:
  void WriteBonded(vtkPointSet* input, double start, const std::vector<double>& times);
  vtkCraterKitLAMMPSDeckWriter(const vtkCraterKitLAMMPSDeckWriter&) = delete;
  void operator=(const vtkCraterKitLAMMPSDeckWriter&) = delete;
};

#endif
