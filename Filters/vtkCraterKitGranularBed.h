/**
 * @class vtkCraterKitGranularBed
 * @brief Source: a granular bed of spheres in a box or hemispherical bowl.
 *
 * HCP lattice (packing fraction 0.7405), a random packing settled with the DEM and
 * brought to rest in the DEM stage's contact law (RCP; without settling, random placement
 * without overlaps), or a loose random packing poured with high friction (Loose);
 * monodisperse, uniform or power-law radii.
 * Thin adapter over craterkit::generateGranularBed (Solvers/bed/GranularBed.h).
 * Output: one vertex per particle with the CraterKit point arrays, and field data
 * recording the container and generation parameters and the measured bulk packing.
 */
#ifndef vtkCraterKitGranularBed_h
#define vtkCraterKitGranularBed_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

class CRATERKITFILTERS_EXPORT vtkCraterKitGranularBed : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitGranularBed* New();
  vtkTypeMacro(vtkCraterKitGranularBed, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum PackingTypes { RCP = 0, HCP = 1, LOOSE = 2 };
  enum ContainerTypes { BOX = 0, BOWL = 1 };
  enum SizeDistributions { MONODISPERSE = 0, UNIFORM = 1, POWER_LAW = 2 };

  vtkSetClampMacro(Packing, int, RCP, LOOSE);
  vtkGetMacro(Packing, int);
  vtkSetClampMacro(Container, int, BOX, BOWL);
  vtkGetMacro(Container, int);
  // Lengths are validated by the solver, not clamped, so bad values get a clear error.
  vtkSetMacro(ContainerRadius, double);
  vtkGetMacro(ContainerRadius, double);
  vtkSetVector3Macro(BoxSize, double);
  vtkGetVector3Macro(BoxSize, double);
  vtkSetMacro(SurfaceHeight, double);
  vtkGetMacro(SurfaceHeight, double);
  vtkSetClampMacro(SizeDistribution, int, MONODISPERSE, POWER_LAW);
  vtkGetMacro(SizeDistribution, int);
  vtkSetMacro(ParticleRadius, double);
  vtkGetMacro(ParticleRadius, double);
  vtkSetMacro(MinRadius, double);
  vtkGetMacro(MinRadius, double);
  vtkSetMacro(MaxRadius, double);
  vtkGetMacro(MaxRadius, double);
  vtkSetMacro(PowerLawExponent, double);
  vtkGetMacro(PowerLawExponent, double);
  vtkSetMacro(PackingFraction, double);
  vtkGetMacro(PackingFraction, double);
  vtkSetMacro(ParticleDensity, double);
  vtkGetMacro(ParticleDensity, double);
  vtkSetMacro(Material, int);
  vtkGetMacro(Material, int);
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  vtkSetMacro(MaxParticles, int);
  vtkGetMacro(MaxParticles, int);
  vtkSetMacro(Settle, int);
  vtkGetMacro(Settle, int);
  vtkSetMacro(SettlingGravity, double);
  vtkGetMacro(SettlingGravity, double);
  vtkSetMacro(SettlingFriction, double);
  vtkGetMacro(SettlingFriction, double);
  vtkSetMacro(DEMMaxExpectedSpeed, double);
  vtkGetMacro(DEMMaxExpectedSpeed, double);
  vtkSetMacro(DEMMaxOverlap, double);
  vtkGetMacro(DEMMaxOverlap, double);
  vtkSetMacro(DEMNormalStiffness, double);
  vtkGetMacro(DEMNormalStiffness, double);

protected:
  vtkCraterKitGranularBed();
  ~vtkCraterKitGranularBed() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Packing = RCP;
  int Container = BOWL;
  double ContainerRadius = 15.0;
  double BoxSize[3] = {10.0, 10.0, 5.0};
  double SurfaceHeight = 0.0;
  int SizeDistribution = MONODISPERSE;
  double ParticleRadius = 0.5;
  double MinRadius = 0.4;
  double MaxRadius = 0.6;
  double PowerLawExponent = 3.0;
  double PackingFraction = 0.56;
  double ParticleDensity = 2000.0;
  int Material = 0;
  int RandomSeed = 1;
  int MaxParticles = 2000000;
  int Settle = 1;
  double SettlingGravity = 9.81;
  double SettlingFriction = 0.1;
  double DEMMaxExpectedSpeed = 1.0;
  double DEMMaxOverlap = 0.01;
  double DEMNormalStiffness = 0.0;

private:
  vtkCraterKitGranularBed(const vtkCraterKitGranularBed&) = delete;
  void operator=(const vtkCraterKitGranularBed&) = delete;
};

#endif
