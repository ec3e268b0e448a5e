/**
 * @class vtkCraterKitBondedImpact
 * @brief Source: hypervelocity impact of a projectile on a plate with the bonded-particle model
 * of Watson & Steinhauser 2017 (Materials 10:379, Eqs. 1-4 and the sizing of Eqs. 5-20).
 *
 * Lattice bodies (projectile sphere or cylinder, square plate) of particles that repel with a
 * cut, shifted Lennard-Jones potential and are held by harmonic bonds that break for good
 * beyond the cut-off. Defaults: the paper's headline case (aluminium sphere D = 9.53 mm at
 * 6.7 km/s on a plate t/D = 0.425, eps = 0.01 J and kappa = 4.56e6 N/m at the paper's sigma,
 * r_cut = 1.5 sigma, to 32 us) at a small particle count. Thin adapter over
 * craterkit::buildBondedImpact, craterkit::BondedRun and craterkit::analyseBondedFragments.
 *
 * Time-dependent: output times 0, OutputInterval, ..., EndTime (the state is the first step at
 * or after the time); an earlier time restarts from a kept snapshot. Output: one vertex per
 * particle with Velocity, Radius, Mass, Density, Material (0 projectile, 1 plate), Id,
 * BondCount (intact bonds), FragmentId (0 the largest) and InternalEnergy (J/kg, with
 * Dissipation ShockViscosity); field data with Time, Step,
 * BrokenBonds, the energies, momentum and the debris-cloud measures of the paper's Section 3.
 */
#ifndef vtkCraterKitBondedImpact_h
#define vtkCraterKitBondedImpact_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

#include <memory>
#include <string>

namespace craterkit {
class BondedRun;
}

class CRATERKITFILTERS_EXPORT vtkCraterKitBondedImpact : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitBondedImpact* New();
  vtkTypeMacro(vtkCraterKitBondedImpact, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Shapes { SPHERE = 0, CYLINDER = 1 };

  vtkSetClampMacro(ProjectileShape, int, SPHERE, CYLINDER);
  vtkGetMacro(ProjectileShape, int);
  vtkSetMacro(Diameter, double);
  vtkGetMacro(Diameter, double);
  vtkSetMacro(CylinderLengthRatio, double);
  vtkGetMacro(CylinderLengthRatio, double);
  vtkSetMacro(ThicknessRatio, double);
  vtkGetMacro(ThicknessRatio, double);
  vtkSetMacro(PlateWidthRatio, double);
  vtkGetMacro(PlateWidthRatio, double);
  vtkSetMacro(ProjectileDensity, double);
  vtkGetMacro(ProjectileDensity, double);
  vtkSetMacro(PlateDensity, double);
  vtkGetMacro(PlateDensity, double);
  vtkSetMacro(ImpactSpeed, double);
  vtkGetMacro(ImpactSpeed, double);
  vtkSetMacro(ImpactAngle, double);
  vtkGetMacro(ImpactAngle, double);
  vtkSetMacro(Spacing, double);
  vtkGetMacro(Spacing, double);
  vtkSetMacro(ParticleCount, double);
  vtkGetMacro(ParticleCount, double);
  vtkSetMacro(Epsilon, double);
  vtkGetMacro(Epsilon, double);
  vtkSetMacro(Kappa, double);
  vtkGetMacro(Kappa, double);
  vtkSetMacro(CutoffRatio, double);
  vtkGetMacro(CutoffRatio, double);
  vtkSetMacro(ReferenceSigma, double);
  vtkGetMacro(ReferenceSigma, double);
  vtkSetMacro(Temperature, double);
  vtkGetMacro(Temperature, double);
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  vtkSetMacro(TimeStep, double);
  vtkGetMacro(TimeStep, double);
  vtkSetMacro(EndTime, double);
  vtkGetMacro(EndTime, double);
  vtkSetMacro(OutputInterval, double);
  vtkGetMacro(OutputInterval, double);
  vtkSetStdStringFromCharMacro(CheckpointFile);
  vtkGetCharFromStdStringMacro(CheckpointFile);
  vtkSetMacro(CheckpointInterval, int);
  vtkGetMacro(CheckpointInterval, int);
  vtkSetMacro(ResumeFromCheckpoint, int);
  vtkGetMacro(ResumeFromCheckpoint, int);
  vtkSetMacro(KeptStates, int);
  vtkGetMacro(KeptStates, int);
  vtkSetMacro(CloudMassFraction, double);
  vtkGetMacro(CloudMassFraction, double);
  // The dissipative term beyond the paper: 0 None (the paper's model), 1 ShockViscosity
  // (craterkit::ShockViscosity, its three parameters below).
  vtkSetMacro(Dissipation, int);
  vtkGetMacro(Dissipation, int);
  vtkSetMacro(ShockViscosityLinear, double);
  vtkGetMacro(ShockViscosityLinear, double);
  vtkSetMacro(ShockViscosityQuadratic, double);
  vtkGetMacro(ShockViscosityQuadratic, double);
  vtkSetMacro(ShockViscosityThreshold, double);
  vtkGetMacro(ShockViscosityThreshold, double);

protected:
  vtkCraterKitBondedImpact();
  ~vtkCraterKitBondedImpact() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCraterKitBondedImpact(const vtkCraterKitBondedImpact&) = delete;
  void operator=(const vtkCraterKitBondedImpact&) = delete;
  void BuildRun();

  int ProjectileShape = SPHERE;
  double Diameter = 9.53e-3;
  double CylinderLengthRatio = 1.0;
  double ThicknessRatio = 0.425;
  double PlateWidthRatio = 4.0;
  double ProjectileDensity = 2700.0;
  double PlateDensity = 2700.0;
  double ImpactSpeed = 6700.0;
  double ImpactAngle = 0.0;
  double Spacing = 0.0;
  double ParticleCount = 1.0e4;
  double Epsilon = 0.01;
  double Kappa = 4.56e6;
  double CutoffRatio = 1.5;
  double ReferenceSigma = 0.0;
  double Temperature = 1e-3;
  int Seed = 1;
  double TimeStep = 0.0;
  double EndTime = 32e-6;
  double OutputInterval = 2e-6;
  std::string CheckpointFile;
  int CheckpointInterval = 0;
  int ResumeFromCheckpoint = 0;
  int KeptStates = 8;
  double CloudMassFraction = 0.95;
  int Dissipation = 0;
  double ShockViscosityLinear = 0.0;
  double ShockViscosityQuadratic = 0.05;
  double ShockViscosityThreshold = 500.0;

  std::unique_ptr<craterkit::BondedRun> Run;
  vtkTimeStamp RunBuildTime;
};

#endif
