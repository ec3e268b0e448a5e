/**
 * @class vtkCraterKitCraterProfile
 * @brief Crater profile and dimensions from a particle state (DEM or SPH).
 *
 * Output 0 (vtkTable): the azimuthally averaged surface height against distance from the
 * impact axis (columns Radius, Height, BinsUsed). Output 1 (vtkPolyData): the particles of
 * the cross-section slab through the axis (|y − axis_y| ≤ SlabHalfWidth), with all their
 * arrays, for rendering. Both carry the summary in field data: CraterDiameter,
 * RimDiameter, CraterDepth, RimHeight, ExcavatedVolume, the same for each side
 * (…Negative for −x, …Positive for +x) and SurfaceHeight. Particle size: the Radius array, or
 * SmoothingLength / 5 (half the SPH spacing at h = 2.5 dx). Thin adapter over
 * craterkit::craterProfile (Solvers/analysis/CraterProfile.h).
 */
#ifndef vtkCraterKitCraterProfile_h
#define vtkCraterKitCraterProfile_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

class CRATERKITFILTERS_EXPORT vtkCraterKitCraterProfile : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitCraterProfile* New();
  vtkTypeMacro(vtkCraterKitCraterProfile, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetMacro(SurfaceFromInput, int);
  vtkGetMacro(SurfaceFromInput, int);
  vtkSetMacro(SurfaceHeight, double);
  vtkGetMacro(SurfaceHeight, double);
  vtkSetVector2Macro(ImpactAxis, double);
  vtkGetVector2Macro(ImpactAxis, double);
  vtkSetMacro(MaxRadius, double);
  vtkGetMacro(MaxRadius, double);
  vtkSetMacro(RadialBins, int);
  vtkGetMacro(RadialBins, int);
  vtkSetMacro(AzimuthalBins, int);
  vtkGetMacro(AzimuthalBins, int);
  vtkSetMacro(SlabHalfWidth, double);
  vtkGetMacro(SlabHalfWidth, double);
  vtkSetMacro(MinNeighbours, int);
  vtkGetMacro(MinNeighbours, int);

protected:
  vtkCraterKitCraterProfile();
  ~vtkCraterKitCraterProfile() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCraterKitCraterProfile(const vtkCraterKitCraterProfile&) = delete;
  void operator=(const vtkCraterKitCraterProfile&) = delete;

  int SurfaceFromInput = 1;
  double SurfaceHeight = 0.0;
  double ImpactAxis[2] = {0.0, 0.0};
  double MaxRadius = 0.0;
  int RadialBins = 0;
  int AzimuthalBins = 16;
  double SlabHalfWidth = 0.0;
  int MinNeighbours = 3;
};

#endif
