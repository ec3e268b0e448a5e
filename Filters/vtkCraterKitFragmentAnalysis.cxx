#include "vtkCraterKitFragmentAnalysis.h"

#include "vtkCraterKitSolverBridge.h"

#include "analysis/Fragments.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

vtkStandardNewMacro(vtkCraterKitFragmentAnalysis);

vtkCraterKitFragmentAnalysis::vtkCraterKitFragmentAnalysis() { this->SetNumberOfOutputPorts(3); }

int vtkCraterKitFragmentAnalysis::FillOutputPortInformation(int port, vtkInformation* info) {
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

int vtkCraterKitFragmentAnalysis::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                              vtkInformationVector* outputVector) {
  using namespace craterkit;
  namespace b = craterkit::bridge;
  vtkPolyData* in = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* out = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  FragmentResult r;
  EjectaStatistics ej;
  double surface = 0.0;
  const bool ok = b::run(this, [&] {
    const vtkIdType n = in ? in->GetNumberOfPoints() : 0;
    if (n == 0)
      throw InputError("FragmentAnalysis: the input has no particles");
    vtkDataArray* radius = in->GetPointData()->GetArray("Radius");
    vtkDataArray* mass = in->GetPointData()->GetArray("Mass");
    vtkDataArray* vel = in->GetPointData()->GetArray("Velocity");
    if (!radius || !mass || !vel || vel->GetNumberOfComponents() != 3)
      throw InputError("FragmentAnalysis: the input needs Radius, Mass and Velocity point arrays");
    std::vector<double> x(3 * n), rad(n), m(n), v(3 * n);
    for (vtkIdType i = 0; i < n; ++i) {
      in->GetPoint(i, &x[3 * i]);
      rad[i] = radius->GetComponent(i, 0);
      m[i] = mass->GetComponent(i, 0);
      vel->GetTuple(i, &v[3 * i]);
    }
    FragmentParams p;
    p.tolerance = this->ContactTolerance;
    for (int k = 0; k < 3; ++k)
      p.axis[k] = this->CloudAxis[k], p.origin[k] = this->CloudOrigin[k];
    p.cloudStart = this->CloudStart;
    if (vtkCellArray* lines = in->GetLines()) {
      auto ids = vtkSmartPointer<vtkIdList>::New();
      for (lines->InitTraversal(); lines->GetNextCell(ids);)
        for (vtkIdType k = 0; k + 1 < ids->GetNumberOfIds(); ++k)
          p.bonds.emplace_back(static_cast<std::size_t>(ids->GetId(k)),
                               static_cast<std::size_t>(ids->GetId(k + 1)));
    }
    r = analyseFragments(x, rad, m, v, p);
    surface = this->SurfaceFromInput
                  ? b::fieldScalar(in->GetFieldData(), "SurfaceHeight", this->SurfaceHeight)
                  : this->SurfaceHeight;
    ej = ejectaStatistics(x, rad, m, v, surface, this->ImpactAxis);
  });
  if (!ok)
    return 0;

  out->ShallowCopy(in);
  std::vector<std::int64_t> ids(r.fragmentId.begin(), r.fragmentId.end());
  out->GetPointData()->AddArray(b::idArray("FragmentId", ids));

  const std::size_t nf = r.fragments.size();
  std::vector<double> mass(nf), centre(3 * nf), velocity(3 * nf);
  std::vector<int> count(nf);
  for (std::size_t k = 0; k < nf; ++k) {
    count[k] = static_cast<int>(r.fragments[k].count);
    mass[k] = r.fragments[k].mass;
    for (int a = 0; a < 3; ++a)
      centre[3 * k + a] = r.fragments[k].centre[a],
                     velocity[3 * k + a] = r.fragments[k].velocity[a];
  }
  table->AddColumn(b::intArray("Count", count));
  table->AddColumn(b::doubleArray("Mass", 1, mass));
  table->AddColumn(b::doubleArray("Centre", 3, centre));
  table->AddColumn(b::doubleArray("Velocity", 3, velocity));
  table->AddColumn(b::doubleArray("CumulativeMassFraction", 1, r.cumulativeMass));

  vtkTable* ejecta = vtkTable::GetData(outputVector, 2);
  ejecta->AddColumn(b::doubleArray("Speed", 1, ej.speed));
  ejecta->AddColumn(b::doubleArray("MassAbove", 1, ej.massAbove));
  for (vtkFieldData* fd : {out->GetFieldData(), table->GetFieldData(), ejecta->GetFieldData()}) {
    b::addField(fd, "EjectaCount", static_cast<double>(ej.count));
    b::addField(fd, "EjectaMass", ej.mass);
    b::addField(fd, "MeanEjectionAngle", ej.meanAngle);
    b::addField(fd, "EjectaSurfaceHeight", surface);
    b::addField(fd, "FragmentCount", static_cast<double>(nf));
    b::addField(fd, "Fragmentation", r.fragmentation);
    b::addField(fd, "LargestMassFraction", r.largestMassFraction);
    b::addField(fd, "CloudParticles", static_cast<double>(r.cloudParticles));
    b::addField(fd, "CloudAxialLength", r.axialLength);
    b::addField(fd, "CloudRadialExtent", r.radialExtent);
    b::addField(fd, "CloudRatio", r.ratio);
    b::addField(fd, "CloudFrontSpeed", r.frontSpeed);
  }
  return 1;
}

void vtkCraterKitFragmentAnalysis::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ContactTolerance: " << this->ContactTolerance << "\n";
  os << indent << "CloudAxis: " << this->CloudAxis[0] << " " << this->CloudAxis[1] << " "
     << this->CloudAxis[2] << "\n";
  os << indent << "CloudOrigin: " << this->CloudOrigin[0] << " " << this->CloudOrigin[1] << " "
     << this->CloudOrigin[2] << "\n";
  os << indent << "CloudStart: " << this->CloudStart << "\n";
  os << indent << "SurfaceFromInput: " << this->SurfaceFromInput << "\n";
  os << indent << "SurfaceHeight: " << this->SurfaceHeight << "\n";
  os << indent << "ImpactAxis: " << this->ImpactAxis[0] << " " << this->ImpactAxis[1] << "\n";
}
