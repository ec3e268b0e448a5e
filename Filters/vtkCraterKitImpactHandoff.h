/**
 * @class vtkCraterKitImpactHandoff
 * @brief The SPH → DEM hand-off: carve the bed with the alpha shape of the compact SPH
 * material, map its momentum onto the bed, add the fast ejecta as particles.
 *
 * Input 0: the SPH state (SPHImpact or a reader: points, Velocity, Mass, optional
 * SmoothingLength; field data TargetShape, TargetRadius, SurfaceHeight, Time, Gravity).
 * Input 1: a settled bed (GranularBed; its field data, such as the container, is passed on).
 * Output 0: the DEM initial state (kept bed + ejecta) with Origin (0 bed, 1 ejecta) and field
 * data with the totals before and after. Output 1: the alpha shape's boundary surface.
 * The SPH state is taken at HandoffTime (negative: the input's last time step); the output
 * is not time-dependent. Thin adapter over craterkit::handoff (Solvers/handoff/Handoff.h).
 */
#ifndef vtkCraterKitImpactHandoff_h
#define vtkCraterKitImpactHandoff_h

#include "CraterKitFiltersModule.h"
#include <vtkPolyDataAlgorithm.h>

class CRATERKITFILTERS_EXPORT vtkCraterKitImpactHandoff : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitImpactHandoff* New();
  vtkTypeMacro(vtkCraterKitImpactHandoff, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The bed on input port 1 (port 0 is the SPH state, SetInputConnection).
  void SetBedConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  vtkSetMacro(EjectaSpeedLimit, double);
  vtkGetMacro(EjectaSpeedLimit, double);
  vtkSetMacro(Alpha, double);
  vtkGetMacro(Alpha, double);
  vtkSetMacro(MinNeighbours, int);
  vtkGetMacro(MinNeighbours, int);
  vtkSetMacro(HandoffTime, double);
  vtkGetMacro(HandoffTime, double);
  vtkSetMacro(EjectaDensity, double);
  vtkGetMacro(EjectaDensity, double);
  enum EjectaModes { ONE_PER_SPH_PARTICLE = 0, GROUPED_TO_BED_SIZE = 1, DROPPED = 2 };
  vtkSetClampMacro(EjectaParticles, int, ONE_PER_SPH_PARTICLE, DROPPED);
  vtkGetMacro(EjectaParticles, int);
  vtkSetMacro(CurtainAsParticles, int);
  vtkGetMacro(CurtainAsParticles, int);
  // Ejecta and curtain whose ballistic flight comes down outside the container leave the domain.
  vtkSetMacro(DropEjectaLandingOutside, int);
  vtkGetMacro(DropEjectaLandingOutside, int);

protected:
  vtkCraterKitImpactHandoff();
  ~vtkCraterKitImpactHandoff() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCraterKitImpactHandoff(const vtkCraterKitImpactHandoff&) = delete;
  void operator=(const vtkCraterKitImpactHandoff&) = delete;

  double EjectaSpeedLimit = 1.0;
  double Alpha = 0.0;
  int MinNeighbours = 1;
  double HandoffTime = -1.0;
  double EjectaDensity = 0.0;
  int EjectaParticles = ONE_PER_SPH_PARTICLE;
  int CurtainAsParticles = 1;
  int DropEjectaLandingOutside = 1;
};

#endif
