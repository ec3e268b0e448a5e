/**
 * @class vtkCraterKitSPHImpact
 * @brief Source: the SPH shock and excavation stage of an impact into a granular target.
 *
 * An impactor sphere (material, mass or radius, speed, angle from the vertical) strikes a
 * porous, cohesionless target (hemisphere or half-space block) under surface gravity.
 * Defaults: the SCI-like case, a 2 kg copper sphere at 2 km/s, vertical, into regolith of
 * 1190 kg/m³ bulk density (friction angle 30°, no cohesion) under Ryugu's 1.5e-4 m/s².
 * Thin adapter over craterkit::buildImpact and craterkit::SphRun (Solvers/sph).
 *
 * Time-dependent: output times 0, OutputInterval, ..., EndTime; asking for a later time
 * advances the run (steps stop exactly there), an earlier one restarts from a kept snapshot.
 * Output: one vertex per SPH particle with Velocity, Density, Mass, Pressure,
 * InternalEnergy, Distention, Damage, DeviatoricStress (symmetric tensor, VTK order XX YY ZZ
 * XY YZ XZ), SmoothingLength, Material (0 impactor, 1 target), Id; field data with Time,
 * Gravity, totals of momentum and energy, the particle spacing and the set-up.
 */
#ifndef vtkCraterKitSPHImpact_h
#define vtkCraterKitSPHImpact_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

#include <memory>
#include <string>

namespace craterkit {
class SphRun;
struct SphImpactSetup;
} // namespace craterkit

class CRATERKITFILTERS_EXPORT vtkCraterKitSPHImpact : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitSPHImpact* New();
  vtkTypeMacro(vtkCraterKitSPHImpact, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum TargetShapes { HALF_SPACE = 0, HEMISPHERE = 1 };
  enum Kernels { CUBIC_SPLINE = 0, WENDLAND_C2 = 1 };

  vtkSetStdStringFromCharMacro(MaterialDirectory);
  vtkGetCharFromStdStringMacro(MaterialDirectory);
  vtkSetStdStringFromCharMacro(ImpactorMaterial);
  vtkGetCharFromStdStringMacro(ImpactorMaterial);
  vtkSetMacro(ImpactorMass, double);
  vtkGetMacro(ImpactorMass, double);
  vtkSetMacro(ImpactorRadius, double);
  vtkGetMacro(ImpactorRadius, double);
  vtkSetMacro(ImpactSpeed, double);
  vtkGetMacro(ImpactSpeed, double);
  vtkSetMacro(ImpactAngle, double);
  vtkGetMacro(ImpactAngle, double);
  vtkSetStdStringFromCharMacro(TargetMaterial);
  vtkGetCharFromStdStringMacro(TargetMaterial);
  vtkSetClampMacro(TargetShape, int, HALF_SPACE, HEMISPHERE);
  vtkGetMacro(TargetShape, int);
  vtkSetMacro(TargetRadius, double);
  vtkGetMacro(TargetRadius, double);

  // Graded target: 1 is one lattice; above 1, shells beyond four impactor radii coarsen in
  // proportion to the distance, up to this multiple of the impactor's spacing.
  vtkSetMacro(TargetCoarsening, double);
  vtkGetMacro(TargetCoarsening, double);
  vtkSetMacro(TargetPorosity, double);
  vtkGetMacro(TargetPorosity, double);
  vtkSetMacro(FrictionAngle, double);
  vtkGetMacro(FrictionAngle, double);
  vtkSetMacro(Cohesion, double);
  vtkGetMacro(Cohesion, double);
  vtkSetMacro(SurfaceGravity, double);
  vtkGetMacro(SurfaceGravity, double);
  vtkSetMacro(TargetContainer, bool);
  vtkGetMacro(TargetContainer, bool);
  vtkBooleanMacro(TargetContainer, bool);
  vtkSetMacro(ParticlesAcrossImpactor, int);
  vtkGetMacro(ParticlesAcrossImpactor, int);
  vtkSetMacro(EndTime, double);
  vtkGetMacro(EndTime, double);
  vtkSetMacro(OutputInterval, double);
  vtkGetMacro(OutputInterval, double);
  vtkSetClampMacro(Kernel, int, CUBIC_SPLINE, WENDLAND_C2);
  vtkGetMacro(Kernel, int);
  vtkSetMacro(ArtificialViscosityAlpha, double);
  vtkGetMacro(ArtificialViscosityAlpha, double);
  vtkSetMacro(ArtificialViscosityBeta, double);
  vtkGetMacro(ArtificialViscosityBeta, double);
  vtkSetMacro(XSPH, double);
  vtkGetMacro(XSPH, double);
  vtkSetMacro(CourantNumber, double);
  vtkGetMacro(CourantNumber, double);
  vtkSetMacro(MinTimeStep, double);
  vtkGetMacro(MinTimeStep, double);
  vtkSetMacro(DomainRadius, double);
  vtkGetMacro(DomainRadius, double);
  vtkSetMacro(LateStageTime, double);
  vtkGetMacro(LateStageTime, double);
  vtkSetMacro(StopImpactorAtLateStage, bool);
  vtkGetMacro(StopImpactorAtLateStage, bool);
  vtkBooleanMacro(StopImpactorAtLateStage, bool);
  vtkSetMacro(LateStageSoundSpeed, double);
  vtkGetMacro(LateStageSoundSpeed, double);
  vtkSetMacro(LateStageInitialSoundSpeed, double);
  vtkGetMacro(LateStageInitialSoundSpeed, double);
  vtkSetMacro(LateStageSoundSpeedExponent, double);
  vtkGetMacro(LateStageSoundSpeedExponent, double);
  vtkSetMacro(LateStagePoissonRatio, double);
  vtkGetMacro(LateStagePoissonRatio, double);
  vtkSetMacro(BlockStepLevels, int);
  vtkGetMacro(BlockStepLevels, int);
  vtkSetStdStringFromCharMacro(CheckpointFile);
  vtkGetCharFromStdStringMacro(CheckpointFile);
  vtkSetMacro(CheckpointInterval, int);
  vtkGetMacro(CheckpointInterval, int);
  vtkSetMacro(ResumeFromCheckpoint, int);
  vtkGetMacro(ResumeFromCheckpoint, int);
  vtkSetMacro(KeptStates, int);
  vtkGetMacro(KeptStates, int);

protected:
  vtkCraterKitSPHImpact();
  ~vtkCraterKitSPHImpact() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCraterKitSPHImpact(const vtkCraterKitSPHImpact&) = delete;
  void operator=(const vtkCraterKitSPHImpact&) = delete;
  craterkit::SphImpactSetup Setup() const; // the properties as the solver's set-up
  void BuildRun();

  // Empty: CRATERKIT_MATERIALS, else the plugin's share/craterkit/materials (installed) or the
  // source tree's data/materials (build tree).
  std::string MaterialDirectory;
  std::string ImpactorMaterial = "copper";
  double ImpactorMass = 2.0;
  double ImpactorRadius = 0.0;
  double ImpactSpeed = 2000.0;
  double ImpactAngle = 0.0;
  std::string TargetMaterial = "regolith";
  int TargetShape = HEMISPHERE;
  double TargetRadius = 0.3;
  double TargetCoarsening = 1.0;
  double TargetPorosity = -1.0;
  double FrictionAngle = 30.0;
  double Cohesion = 0.0;
  double SurfaceGravity = 1.5e-4;
  int ParticlesAcrossImpactor = 4;
  bool TargetContainer = false;
  std::size_t ContainerParticles = 0; // the last ones of the run's state; not in the output
  double EndTime = 5e-4;
  double OutputInterval = 5e-5;
  int Kernel = CUBIC_SPLINE;
  double ArtificialViscosityAlpha = 1.0;
  double ArtificialViscosityBeta = 2.0;
  double XSPH = 0.0;
  double CourantNumber = 0.3;
  double MinTimeStep = 1e-12;
  double LateStageTime = -1.0;
  bool StopImpactorAtLateStage = false;
  double DomainRadius = 0.0;
  double LateStageSoundSpeed = 100.0;
  double LateStageInitialSoundSpeed = 0.0;
  double LateStageSoundSpeedExponent = 0.6;
  double LateStagePoissonRatio = -1.0;
  int BlockStepLevels = 0;
  std::string CheckpointFile;
  int CheckpointInterval = 0;
  int ResumeFromCheckpoint = 0;
  int KeptStates = 8;

  std::unique_ptr<craterkit::SphRun> Run;
  double Spacing = 0.0;
  vtkTimeStamp RunBuildTime;
};

#endif
