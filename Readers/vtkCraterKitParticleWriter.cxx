#include "vtkCraterKitParticleWriter.h"

#include "vtkCraterKitSolverBridge.h"

#include "common/AtomicWrite.h"
#include "io/LammpsDump.h"
#include "io/PkdgravSs.h"

#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cctype>
#include <ostream>
#include <set>

vtkStandardNewMacro(vtkCraterKitParticleWriter);

vtkCraterKitParticleWriter::vtkCraterKitParticleWriter() = default;

vtkCraterKitParticleWriter::~vtkCraterKitParticleWriter() { this->SetFileName(nullptr); }

int vtkCraterKitParticleWriter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkCraterKitParticleWriter::WriteData() {
  using namespace craterkit;
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  const bool ok = bridge::run(this, [&] {
    if (!this->FileName || !*this->FileName)
      throw InputError("no file name");
    ParticleFrame frame;
    frame.particles = bridge::fromPolyData(input);
    frame.time = bridge::fieldScalar(input->GetFieldData(), "Time", 0.0);
    frame.timestep =
        static_cast<long long>(bridge::fieldScalar(input->GetFieldData(), "TimeStep", 0.0));
    // Every other numeric point array travels with the particles.
    static const std::set<std::string> model = {"Velocity", "AngularVelocity", "Radius", "Mass",
                                                "Density",  "Material",        "Id"};
    vtkPointData* pd = input->GetPointData();
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
      vtkDataArray* array = pd->GetArray(a);
      if (!array || !array->GetName() || model.count(array->GetName()))
        continue;
      std::string name = array->GetName();
      for (char& c : name)
        if (std::isspace(static_cast<unsigned char>(c)))
          c = '_';
      ExtraArray x{name, array->GetNumberOfComponents(), {}};
      x.values.resize(static_cast<std::size_t>(array->GetNumberOfTuples()) * x.components);
      for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
        for (int k = 0; k < x.components; ++k)
          x.values[static_cast<std::size_t>(i) * x.components + k] = array->GetComponent(i, k);
      frame.extra.push_back(std::move(x));
    }
    std::string name = this->FileName, lower = name;
    for (char& c : lower)
      c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool ss = lower.size() >= 3 && lower.compare(lower.size() - 3, 3, ".ss") == 0;
    const std::string bytes = ss ? writeSs(frame, this->PkdgravUnits != 0) : writeDump(frame);
    // Write beside, then rename: a failed write never leaves half a file under the name.
    writeFileAtomically(name, ss ? "the .ss file" : "the dump", [&](std::ostream& out) {
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
  });
  if (!ok)
    this->SetErrorCode(1);
}

void vtkCraterKitParticleWriter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "PkdgravUnits: " << this->PkdgravUnits << "\n";
}
