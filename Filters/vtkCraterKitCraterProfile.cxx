#include "vtkCraterKitCraterProfile.h"

#include "vtkCraterKitSolverBridge.h"

#include "analysis/CraterProfile.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include <cmath>

vtkStandardNewMacro(vtkCraterKitCraterProfile);

vtkCraterKitCraterProfile::vtkCraterKitCraterProfile() { this->SetNumberOfOutputPorts(2); }

int vtkCraterKitCraterProfile::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

int vtkCraterKitCraterProfile::FillOutputPortInformation(int port, vtkInformation* info) {
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkTable" : "vtkPolyData");
  return 1;
}

int vtkCraterKitCraterProfile::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector) {
  using namespace craterkit;
  namespace b = craterkit::bridge;
  vtkPointSet* in = vtkPointSet::GetData(inputVector[0], 0);
  vtkTable* table = vtkTable::GetData(outputVector, 0);
  vtkPolyData* section = vtkPolyData::GetData(outputVector, 1);
  CraterProfileResult r;
  CraterProfileParams p;
  const bool ok = b::run(this, [&] {
    const vtkIdType n = in ? in->GetNumberOfPoints() : 0;
    if (n == 0)
      throw InputError("CraterProfile: the input has no particles");
    vtkDataArray* radius = in->GetPointData()->GetArray("Radius");
    vtkDataArray* h = in->GetPointData()->GetArray("SmoothingLength");
    if (!radius && !h)
      throw InputError(
          "CraterProfile: the input needs a Radius (DEM) or SmoothingLength (SPH) point array");
    std::vector<double> x(3 * n), rad(n);
    for (vtkIdType i = 0; i < n; ++i) {
      in->GetPoint(i, &x[3 * i]);
      rad[i] = radius ? radius->GetComponent(i, 0) : h->GetComponent(i, 0) / 5.0;
    }
    p.axis[0] = this->ImpactAxis[0];
    p.axis[1] = this->ImpactAxis[1];
    p.surfaceHeight = this->SurfaceFromInput
                          ? b::fieldScalar(in->GetFieldData(), "SurfaceHeight", this->SurfaceHeight)
                          : this->SurfaceHeight;
    p.maxRadius = this->MaxRadius;
    p.radialBins = this->RadialBins;
    p.azimuthalBins = this->AzimuthalBins;
    p.slabHalfWidth = this->SlabHalfWidth;
    p.minNeighbours = this->MinNeighbours;
    r = craterProfile(x, rad, p);
  });
  if (!ok)
    return 0;

  table->AddColumn(b::doubleArray("Radius", 1, r.radius));
  table->AddColumn(b::doubleArray("Height", 1, r.height));
  table->AddColumn(b::intArray("BinsUsed", r.binsUsed));

  // The slab: the input's particles with all their arrays.
  std::vector<double> xyz(3 * r.slab.size());
  for (std::size_t k = 0; k < r.slab.size(); ++k)
    in->GetPoint(static_cast<vtkIdType>(r.slab[k]), &xyz[3 * k]);
  b::setVertices(section, xyz);
  section->GetPointData()->CopyAllocate(in->GetPointData(), static_cast<vtkIdType>(r.slab.size()));
  for (std::size_t k = 0; k < r.slab.size(); ++k)
    section->GetPointData()->CopyData(in->GetPointData(), static_cast<vtkIdType>(r.slab[k]),
                                      static_cast<vtkIdType>(k));

  for (vtkFieldData* fd : {table->GetFieldData(), section->GetFieldData()}) {
    fd->ShallowCopy(in->GetFieldData());
    auto put = [&](const char* suffix, const CraterMeasures& m) {
      const std::string s = suffix;
      b::addField(fd, ("CraterFound" + s).c_str(), m.found ? 1.0 : 0.0);
      b::addField(fd, ("CraterDiameter" + s).c_str(), m.diameter);
      b::addField(fd, ("RimDiameter" + s).c_str(), m.rimDiameter);
      b::addField(fd, ("CraterDepth" + s).c_str(), m.depth);
      b::addField(fd, ("RimHeight" + s).c_str(), m.rimHeight);
      b::addField(fd, ("ExcavatedVolume" + s).c_str(), m.volume);
      b::addField(fd, ("CraterDepthBelowRim" + s).c_str(), m.depthBelowRim);
    };
    put("", r.all);
    put("Negative", r.negativeHalf);
    put("Positive", r.positiveHalf);
    b::addField(fd, "DeepestPointDepth", r.deepestDepth);
    b::addField(fd, "DeepestPointDepthBelowRim", r.deepestDepthBelowRim);
    b::addField(fd, "SurfaceHeight", p.surfaceHeight);
    b::addField(fd, "RejectedAsEjecta", static_cast<double>(r.rejectedAsEjecta));
    b::addField(fd, "ImpactAxis", this->ImpactAxis, 2);
  }
  if (!r.all.found && r.all.depth > 0.0)
    vtkWarningMacro(
        << "no crater diameter: the surface dips " << r.all.depth << " m below SurfaceHeight ("
        << p.surfaceHeight
        << " m) but does not rise back to it within the profile (the "
           "surface around the pit lies below the original level, or the crater is wider than "
           "the particles reach)");
  else if (!r.all.found)
    vtkWarningMacro(<< "no crater: the surface never dips below SurfaceHeight (" << p.surfaceHeight
                    << " m)");
  return 1;
}

void vtkCraterKitCraterProfile::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SurfaceFromInput: " << this->SurfaceFromInput << "\n";
  os << indent << "SurfaceHeight: " << this->SurfaceHeight << "\n";
  os << indent << "ImpactAxis: " << this->ImpactAxis[0] << " " << this->ImpactAxis[1] << "\n";
  os << indent << "MaxRadius: " << this->MaxRadius << "\n";
  os << indent << "RadialBins: " << this->RadialBins << "\n";
  os << indent << "AzimuthalBins: " << this->AzimuthalBins << "\n";
  os << indent << "SlabHalfWidth: " << this->SlabHalfWidth << "\n";
  os << indent << "MinNeighbours: " << this->MinNeighbours << "\n";
}
