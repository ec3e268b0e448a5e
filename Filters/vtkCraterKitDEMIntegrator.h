/**
 * @class vtkCraterKitDEMIntegrator
 * @brief Soft-sphere DEM (pkdgrav's SSDEM model) as a time-dependent filter.
 *
 * Input: particles with the CraterKit arrays (Radius and Mass or Density required;
 * Velocity, AngularVelocity, Material, Id optional). Output: the particles at the
 * requested time. The filter advertises output times from the input's Time (field data,
 * default 0) to EndTime every OutputInterval, advances when a later time is requested and
 * restarts from kept in-memory snapshots (or the input) when an earlier one is. Thin
 * adapter over craterkit::DemRun (Solvers/dem/DemRun.h).
 */
#ifndef vtkCraterKitDEMIntegrator_h
#define vtkCraterKitDEMIntegrator_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

#include <memory>
#include <string>

namespace craterkit {
class DemRun;
}

class CRATERKITFILTERS_EXPORT vtkCraterKitDEMIntegrator : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitDEMIntegrator* New();
  vtkTypeMacro(vtkCraterKitDEMIntegrator, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ContactLaws { LINEAR_SPRING_DASHPOT = 0, HERTZ = 1 };
  enum Containers { FROM_INPUT = 0, NO_WALLS = 1, BOX = 2, BOWL = 3, CYLINDER = 4 };
  enum GravityModels { NO_GRAVITY = 0, UNIFORM = 1, POINT_MASS = 2 };

  vtkSetClampMacro(ContactLaw, int, LINEAR_SPRING_DASHPOT, HERTZ);
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
  vtkSetClampMacro(Container, int, FROM_INPUT, CYLINDER);
  vtkGetMacro(Container, int);
  vtkSetMacro(ContainerRadius, double);
  vtkGetMacro(ContainerRadius, double);
  vtkSetVector3Macro(BoxSize, double);
  vtkGetVector3Macro(BoxSize, double);
  vtkSetClampMacro(GravityModel, int, NO_GRAVITY, POINT_MASS);
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
  vtkSetStdStringFromCharMacro(CheckpointFile);
  vtkGetCharFromStdStringMacro(CheckpointFile);
  vtkSetMacro(CheckpointInterval, int);
  vtkGetMacro(CheckpointInterval, int);
  vtkSetMacro(ResumeFromCheckpoint, int);
  vtkGetMacro(ResumeFromCheckpoint, int);
  vtkSetMacro(KeptStates, int);
  vtkGetMacro(KeptStates, int);

protected:
  vtkCraterKitDEMIntegrator();
  ~vtkCraterKitDEMIntegrator() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int ContactLaw = LINEAR_SPRING_DASHPOT;
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
  int Container = FROM_INPUT;
  double ContainerRadius = 15.0;
  double BoxSize[3] = {10.0, 10.0, 5.0};
  int GravityModel = UNIFORM;
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
  std::string CheckpointFile;
  int CheckpointInterval = 10000;
  int ResumeFromCheckpoint = 0;
  int KeptStates = 16;

private:
  vtkCraterKitDEMIntegrator(const vtkCraterKitDEMIntegrator&) = delete;
  void operator=(const vtkCraterKitDEMIntegrator&) = delete;
  void BuildRun(vtkPolyData* input);

  std::unique_ptr<craterkit::DemRun> Run;
  vtkTimeStamp RunBuildTime;
  std::size_t WarningsShown = 0;
};

#endif
