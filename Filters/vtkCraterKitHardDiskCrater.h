/**
 * @class vtkCraterKitHardDiskCrater
 * @brief Source: the 2D event-driven hard-disk crater model ("ball pit").
 *
 * A ground of hard disks at rest (random, at a chosen area fraction) is struck by one
 * large disk or a clump of small disks; the run is event-driven and stops exactly at
 * evenly spaced frame times, which the source advertises as its time steps. Thin adapter
 * over craterkit::HardDiskCraterRun (Solvers/edmd/HardDiskCrater.h).
 *
 * The model plane is x-z (z up) so that 3D filters and views treat it like a slice of a
 * bed. Output 0: the disks (Velocity, Radius, Mass, Density, Material 0 ground / 1
 * impactor, Id, IsTracer, Disturbed). Output 1: the tracer paths as polylines up to the
 * current frame. Output 2: the transient crater outline (top of the ground per bin).
 * Field data: the frame's time, collision counts, energy, shock-front radius, the mean
 * ejection angle of disks that crossed the original surface, crater depth and width.
 */
#ifndef vtkCraterKitHardDiskCrater_h
#define vtkCraterKitHardDiskCrater_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

#include <memory>

namespace craterkit {
class HardDiskCraterRun;
}

class CRATERKITFILTERS_EXPORT vtkCraterKitHardDiskCrater : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitHardDiskCrater* New();
  vtkTypeMacro(vtkCraterKitHardDiskCrater, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Presets { CUSTOM = 0, BALL_PIT = 1, DENSE_SAND = 2, CLUMP_IMPACTOR = 3 };
  enum ImpactorTypes { DISK = 0, CLUMP = 1 };

  vtkSetClampMacro(Preset, int, CUSTOM, CLUMP_IMPACTOR);
  vtkGetMacro(Preset, int);
  vtkSetMacro(Width, double);
  vtkGetMacro(Width, double);
  vtkSetMacro(GroundDepth, double);
  vtkGetMacro(GroundDepth, double);
  vtkSetMacro(Headroom, double);
  vtkGetMacro(Headroom, double);
  vtkSetMacro(DiskRadius, double);
  vtkGetMacro(DiskRadius, double);
  vtkSetMacro(MaxDiskRadius, double);
  vtkGetMacro(MaxDiskRadius, double);
  vtkSetMacro(AreaFraction, double);
  vtkGetMacro(AreaFraction, double);
  vtkSetMacro(GroundDensity, double);
  vtkGetMacro(GroundDensity, double);
  vtkSetClampMacro(ImpactorType, int, DISK, CLUMP);
  vtkGetMacro(ImpactorType, int);
  vtkSetMacro(ImpactorRadius, double);
  vtkGetMacro(ImpactorRadius, double);
  vtkSetMacro(DensityRatio, double);
  vtkGetMacro(DensityRatio, double);
  vtkSetMacro(ImpactSpeed, double);
  vtkGetMacro(ImpactSpeed, double);
  vtkSetMacro(ImpactAngle, double);
  vtkGetMacro(ImpactAngle, double);
  vtkSetMacro(Restitution, double);
  vtkGetMacro(Restitution, double);
  vtkSetMacro(Gravity, double);
  vtkGetMacro(Gravity, double);
  vtkSetMacro(FrameInterval, double);
  vtkGetMacro(FrameInterval, double);
  vtkSetMacro(EndTime, double);
  vtkGetMacro(EndTime, double);
  vtkSetMacro(TracerFraction, double);
  vtkGetMacro(TracerFraction, double);
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);

protected:
  vtkCraterKitHardDiskCrater();
  ~vtkCraterKitHardDiskCrater() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Preset = CUSTOM;
  double Width = 1.0;
  double GroundDepth = 0.5;
  double Headroom = 0.5;
  double DiskRadius = 0.005;
  double MaxDiskRadius = 0.0;
  double AreaFraction = 0.7;
  double GroundDensity = 1000.0;
  int ImpactorType = DISK;
  double ImpactorRadius = 0.03;
  double DensityRatio = 3.0;
  double ImpactSpeed = 10.0;
  double ImpactAngle = 0.0;
  double Restitution = 1.0;
  double Gravity = 0.0;
  double FrameInterval = 0.001;
  double EndTime = 0.1;
  double TracerFraction = 0.02;
  int RandomSeed = 1;

private:
  vtkCraterKitHardDiskCrater(const vtkCraterKitHardDiskCrater&) = delete;
  void operator=(const vtkCraterKitHardDiskCrater&) = delete;
  std::unique_ptr<craterkit::HardDiskCraterRun> Run;
  vtkTimeStamp RunBuildTime;
};

#endif
