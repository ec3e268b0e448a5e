/**
 * @class vtkCraterKitFragmentAnalysis
 * @brief Fragments (connected particles) and the debris cloud of a particle state.
 *
 * Particles are linked by contact (centres within (r_i + r_j)(1 + ContactTolerance)) or, when
 * the input has line cells, by those lines (bonds). Output 0: the particles with a FragmentId
 * point array (0 = the heaviest fragment). Output 1 (vtkTable): one row per fragment (Count,
 * Mass, Centre, Velocity, CumulativeMassFraction). Field data: FragmentCount, Fragmentation
 * F = N_fragments / N_particles, LargestMassFraction, and for the particles past CloudStart
 * along CloudAxis: CloudParticles, CloudAxialLength, CloudRadialExtent, CloudRatio (L_a / L_r)
 * and CloudFrontSpeed. Output 2 (vtkTable): crater ejecta (particles above the original
 * surface moving up): Speed (decreasing) and MassAbove; field data EjectaCount, EjectaMass,
 * MeanEjectionAngle (degrees from the horizontal, mass-weighted; the Z-model gives 45° for
 * Z = 3). Thin adapter over craterkit::analyseFragments and craterkit::ejectaStatistics.
 */
#ifndef vtkCraterKitFragmentAnalysis_h
#define vtkCraterKitFragmentAnalysis_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

class CRATERKITFILTERS_EXPORT vtkCraterKitFragmentAnalysis : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitFragmentAnalysis* New();
  vtkTypeMacro(vtkCraterKitFragmentAnalysis, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetMacro(ContactTolerance, double);
  vtkGetMacro(ContactTolerance, double);
  vtkSetVector3Macro(CloudAxis, double);
  vtkGetVector3Macro(CloudAxis, double);
  vtkSetVector3Macro(CloudOrigin, double);
  vtkGetVector3Macro(CloudOrigin, double);
  vtkSetMacro(CloudStart, double);
  vtkGetMacro(CloudStart, double);
  vtkSetMacro(SurfaceFromInput, int);
  vtkGetMacro(SurfaceFromInput, int);
  vtkSetMacro(SurfaceHeight, double);
  vtkGetMacro(SurfaceHeight, double);
  vtkSetVector2Macro(ImpactAxis, double);
  vtkGetVector2Macro(ImpactAxis, double);

protected:
  vtkCraterKitFragmentAnalysis();
  ~vtkCraterKitFragmentAnalysis() override = default;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCraterKitFragmentAnalysis(const vtkCraterKitFragmentAnalysis&) = delete;
  void operator=(const vtkCraterKitFragmentAnalysis&) = delete;

  double ContactTolerance = 0.01;
  double CloudAxis[3] = {0.0, 0.0, -1.0};
  double CloudOrigin[3] = {0.0, 0.0, 0.0};
  double CloudStart = 0.0;
  int SurfaceFromInput = 1;
  double SurfaceHeight = 0.0;
  double ImpactAxis[2] = {0.0, 0.0};
};

#endif
