#include "vtkCraterKitParticleReader.h"

#include "vtkCraterKitSolverBridge.h"

#include "dem/DemCheckpoint.h"
#include "io/FileBytes.h"
#include "io/LammpsDump.h"
#include "io/PkdgravSs.h"
#include "sph/SphCheckpoint.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCraterKitParticleReader);

struct vtkCraterKitParticleReader::Cache {
  std::string File;
  int Format = 0;
  int Units = 1;
  std::string Bytes; // a dump of several snapshots (a copy: the file may be rewritten meanwhile)
  std::vector<craterkit::DumpIndexEntry> Index;
  std::unique_ptr<craterkit::ParticleFrame> Single;
  std::vector<double> Times;
};

namespace {
std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

int FormatOf(const std::string& name) {
  std::string n = Lower(name);
  if (EndsWith(n, ".gz"))
    n.resize(n.size() - 3);
  if (EndsWith(n, ".ss"))
    return vtkCraterKitParticleReader::PKDGRAV_SS;
  if (EndsWith(n, ".ckdem") || EndsWith(n, ".cksph"))
    return vtkCraterKitParticleReader::CRATERKIT_CHECKPOINT;
  const std::string base =
      n.substr(n.find_last_of('/') == std::string::npos ? 0 : n.find_last_of('/') + 1);
  if (EndsWith(n, ".dump") || EndsWith(n, ".liggghts") || EndsWith(n, ".lammpstrj") ||
      base.find("dump") != std::string::npos)
    return vtkCraterKitParticleReader::LAMMPS_DUMP;
  return vtkCraterKitParticleReader::AUTOMATIC;
}

// An SPH checkpoint (SPHImpact): positions, Velocity, Mass, Density, Material, Id and the SPH
// state as extra arrays (Pressure is not stored: it follows from the material's equation of state).
craterkit::ParticleFrame FrameOfSphCheckpoint(const std::string& path,
                                              std::vector<std::string>& warnings) {
  using namespace craterkit;
  double time = 0.0, next = 0.0;
  std::size_t steps = 0;
  std::string warning;
  const SphState s = readSphCheckpoint(path, time, steps, next, &warning);
  if (!warning.empty())
    warnings.push_back(warning);
  ParticleFrame f;
  f.time = time;
  f.timestep = static_cast<long long>(steps);
  ParticleSet& p = f.particles;
  const std::size_t n = s.size();
  p.position = s.x;
  p.velocity = s.v;
  p.angularVelocity.assign(3 * n, 0.0);
  p.radius.assign(n, 0.0);
  p.mass = s.mass;
  p.density = s.rho;
  p.material = s.material;
  p.id.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    p.id[i] = static_cast<std::int64_t>(i);
  f.hasVelocity = f.hasMass = f.hasDensity = f.hasMaterial = f.hasId = true;
  std::vector<double> stress(6 * n);
  for (std::size_t i = 0; i < n; ++i) // VTK symmetric-tensor order XX YY ZZ XY YZ XZ
  {
    const double* S = &s.S[6 * i];
    double* o = &stress[6 * i];
    o[0] = S[0], o[1] = S[1], o[2] = S[2], o[3] = S[3], o[4] = S[5], o[5] = S[4];
  }
  f.extra = {{"SmoothingLength", 1, s.h},
             {"InternalEnergy", 1, s.u},
             {"Distention", 1, s.alpha},
             {"Damage", 1, s.damage},
             {"DeviatoricStress", 6, stress}};
  return f;
}

// A checkpoint whose checksum fails is refused (InputError naming the file); an old one
// without a checksum reads with WARNINGS.
craterkit::ParticleFrame FrameOfCheckpoint(const std::string& path,
                                           std::vector<std::string>& warnings) {
  if (EndsWith(Lower(path), ".cksph"))
    return FrameOfSphCheckpoint(path, warnings);
  craterkit::DemCheckpointState state = craterkit::readDemCheckpointState(path);
  warnings.insert(warnings.end(), state.warnings.begin(), state.warnings.end());
  craterkit::ParticleFrame f;
  f.particles = std::move(state.particles);
  f.time = state.time;
  f.timestep = state.step;
  f.hasVelocity = f.hasAngularVelocity = f.hasRadius = f.hasMass = f.hasDensity = f.hasMaterial =
      f.hasId = true;
  return f;
}
} // namespace

vtkCraterKitParticleReader::vtkCraterKitParticleReader() { this->SetNumberOfInputPorts(0); }

vtkCraterKitParticleReader::~vtkCraterKitParticleReader() { this->SetFileName(nullptr); }

int vtkCraterKitParticleReader::CanReadFile(const char* name) {
  return name && FormatOf(name) != AUTOMATIC ? 1 : 0;
}

void vtkCraterKitParticleReader::Load() {
  using namespace craterkit;
  if (!this->FileName || !*this->FileName)
    throw InputError("no file name");
  const std::string file = this->FileName;
  const int format = this->Format != AUTOMATIC ? this->Format : FormatOf(file);
  if (this->Loaded && this->Loaded->File == file && this->Loaded->Format == format &&
      this->Loaded->Units == this->PkdgravUnits)
    return;
  this->Loaded.reset();
  auto cache = std::make_unique<Cache>();
  cache->File = file;
  cache->Format = format;
  cache->Units = this->PkdgravUnits;
  switch (format) {
  case LAMMPS_DUMP: {
    // Parsed in place from the memory map; only a dump of several snapshots is kept (copied).
    const FileBytes bytes(file);
    cache->Index = indexDump(bytes.view(), file);
    if (cache->Index.size() == 1)
      cache->Single =
          std::make_unique<ParticleFrame>(parseDumpSnapshot(bytes.view(), cache->Index[0], file));
    else
      cache->Bytes.assign(bytes.view());
    for (const DumpIndexEntry& e : cache->Index)
      cache->Times.push_back(e.time);
    break;
  }
  case PKDGRAV_SS:
    cache->Single = std::make_unique<ParticleFrame>(
        parseSs(FileBytes(file).view(), file, this->PkdgravUnits != 0));
    cache->Times.push_back(cache->Single->time);
    break;
  case CRATERKIT_CHECKPOINT: {
    std::vector<std::string> warnings;
    cache->Single = std::make_unique<ParticleFrame>(FrameOfCheckpoint(file, warnings));
    for (const std::string& w : warnings)
      vtkWarningMacro(<< w);
    cache->Times.push_back(cache->Single->time);
    break;
  }
  default:
    throw InputError(file + ": unknown particle format (extensions: .dump, .liggghts, .lammpstrj, "
                            ".ss, .ckdem, .cksph, optionally .gz); set Format");
  }
  // Time steps must increase; a dump whose snapshots do not gets their indices instead.
  for (std::size_t k = 1; k < cache->Times.size(); ++k)
    if (!(cache->Times[k] > cache->Times[k - 1])) {
      vtkWarningMacro(<< file
                      << ": snapshot times do not increase; using snapshot numbers as times");
      for (std::size_t j = 0; j < cache->Times.size(); ++j)
        cache->Times[j] = static_cast<double>(j);
      break;
    }
  this->Loaded = std::move(cache);
}

int vtkCraterKitParticleReader::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                   vtkInformationVector* outputVector) {
  if (!craterkit::bridge::run(this, [&] { this->Load(); }))
    return 0;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const std::vector<double>& times = this->Loaded->Times;
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
               static_cast<int>(times.size()));
  const double range[2] = {times.front(), times.back()};
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

int vtkCraterKitParticleReader::RequestData(vtkInformation*, vtkInformationVector**,
                                            vtkInformationVector* outputVector) {
  using namespace craterkit;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  ParticleFrame parsed;
  const ParticleFrame* shown = &parsed;
  std::size_t snapshot = 0;
  const bool ok = bridge::run(this, [&] {
    this->Load();
    const std::vector<double>& times = this->Loaded->Times;
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())) {
      const double t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      // The last snapshot at or before t.
      const auto it = std::upper_bound(times.begin(), times.end(), t + 1e-12 * std::abs(t));
      snapshot = it == times.begin() ? 0 : static_cast<std::size_t>(it - times.begin()) - 1;
    }
    if (this->Loaded->Single)
      shown = this->Loaded->Single.get();
    else
      parsed =
          parseDumpSnapshot(this->Loaded->Bytes, this->Loaded->Index[snapshot], this->Loaded->File);
  });
  if (!ok)
    return 0;

  const ParticleFrame& frame = *shown;
  bridge::toPolyData(frame.particles, output);
  vtkPointData* pd = output->GetPointData();
  if (!frame.hasVelocity)
    pd->RemoveArray("Velocity");
  if (!frame.hasAngularVelocity)
    pd->RemoveArray("AngularVelocity");
  if (!frame.hasRadius)
    pd->RemoveArray("Radius");
  if (!frame.hasMass)
    pd->RemoveArray("Mass");
  if (!frame.hasDensity)
    pd->RemoveArray("Density");
  for (const ExtraArray& x : frame.extra)
    if (!pd->HasArray(x.name.c_str()))
      pd->AddArray(bridge::doubleArray(x.name.c_str(), x.components, x.values));
  if (pd->HasArray("Radius"))
    pd->SetActiveScalars("Radius");
  vtkFieldData* fd = output->GetFieldData();
  bridge::addField(fd, "Time", frame.time);
  bridge::addField(fd, "TimeStep", static_cast<double>(frame.timestep));
  bridge::addField(fd, "Snapshot", static_cast<double>(snapshot));
  if (frame.hasBox)
    bridge::addField(fd, "BoxBounds", frame.box, 6);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), this->Loaded->Times[snapshot]);
  return 1;
}

void vtkCraterKitParticleReader::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Format: " << this->Format << "\n";
  os << indent << "PkdgravUnits: " << this->PkdgravUnits << "\n";
}
