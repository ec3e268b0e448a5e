// Conversions between CraterKit solver state and VTK data, and the one place where
// solver exceptions become VTK errors. The header-only CraterKit::Bridge module, which the
// CraterKit::Filters and CraterKit::Readers modules both depend on.
#pragma once

#include "common/Error.h"
#include "common/NamedValue.h"
#include "common/ParticleSet.h"
#include "common/Progress.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIndent.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkTimeStamp.h>
#include <vtkTypeInt64Array.h>

#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace craterkit {
namespace bridge {

inline vtkSmartPointer<vtkDoubleArray> doubleArray(const char* name, int components,
                                                   const std::vector<double>& values) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

inline vtkSmartPointer<vtkIntArray> intArray(const char* name, const std::vector<int>& values) {
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

inline vtkSmartPointer<vtkTypeInt64Array> idArray(const char* name,
                                                  const std::vector<std::int64_t>& values) {
  auto array = vtkSmartPointer<vtkTypeInt64Array>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

// Points (3 doubles each) with one vertex cell per point.
inline void setVertices(vtkPolyData* out, const std::vector<double>& xyz) {
  const vtkIdType n = static_cast<vtkIdType>(xyz.size() / 3);
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  std::copy(xyz.begin(), xyz.end(), static_cast<double*>(points->GetData()->GetVoidPointer(0)));
  out->SetPoints(points);
  auto offsets = vtkSmartPointer<vtkTypeInt64Array>::New();
  auto connectivity = vtkSmartPointer<vtkTypeInt64Array>::New();
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(n, n);
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  out->SetVerts(verts);
}

// Points (3 doubles each) joined in order into polylines of counts[k] points each.
template <class Count> void setPolyLines(vtkPolyData* out, const std::vector<double>& xyz,
                                         const std::vector<Count>& counts) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  vtkIdType next = 0;
  for (const Count count : counts) {
    lines->InsertNextCell(static_cast<vtkIdType>(count));
    for (Count k = 0; k < count; ++k, ++next) {
      lines->InsertCellPoint(points->GetNumberOfPoints());
      points->InsertNextPoint(&xyz[3 * next]);
    }
  }
  out->SetPoints(points);
  out->SetLines(lines);
}

// Points (3 doubles each) and triangles (3 point indices each).
inline void setTriangles(vtkPolyData* out, const std::vector<double>& xyz,
                         const std::vector<long long>& triangles) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(xyz.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    points->SetPoint(i, &xyz[3 * i]);
  auto tris = vtkSmartPointer<vtkCellArray>::New();
  for (std::size_t k = 0; k + 2 < triangles.size(); k += 3)
    tris->InsertNextCell({static_cast<vtkIdType>(triangles[k]),
                          static_cast<vtkIdType>(triangles[k + 1]),
                          static_cast<vtkIdType>(triangles[k + 2])});
  out->SetPoints(points);
  out->SetPolys(tris);
}

// Output times start, start + interval, ..., end (end included), at most `limit` of them.
inline std::vector<double> outputTimes(double start, double end, double interval,
                                       long limit = 1000000) {
  std::vector<double> times{start};
  if (!(interval > 0.0) || !(end > start) || !std::isfinite(end))
    return times;
  const long count = static_cast<long>(std::floor((end - start) / interval + 1e-9));
  for (long k = 1; k <= count && k < limit; ++k)
    times.push_back(start + k * interval);
  if (end - times.back() > 1e-9 * interval)
    times.push_back(end);
  return times;
}

// Announces the output times (their first to last as the range).
inline void setTimeSteps(vtkInformation* info, const std::vector<double>& times) {
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
            static_cast<int>(times.size()));
  const double range[2] = {times.front(), times.back()};
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
}

// The time a request asks for, else `fallback`.
inline double requestedTime(vtkInformation* info, double fallback) {
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
             ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
             : fallback;
}

// Particles as vertices with the point arrays of docs/architecture.md ("Data model").
inline void toPolyData(const ParticleSet& s, vtkPolyData* out) {
  setVertices(out, s.position);
  vtkPointData* pd = out->GetPointData();
  pd->AddArray(doubleArray("Velocity", 3, s.velocity));
  pd->AddArray(doubleArray("AngularVelocity", 3, s.angularVelocity));
  pd->AddArray(doubleArray("Radius", 1, s.radius));
  pd->AddArray(doubleArray("Mass", 1, s.mass));
  pd->AddArray(doubleArray("Density", 1, s.density));
  pd->AddArray(intArray("Material", s.material));
  pd->AddArray(idArray("Id", s.id));
  pd->SetActiveScalars("Radius");
}

// Reads particles from point data; throws InputError naming a missing or malformed array.
inline ParticleSet fromPolyData(vtkPointSet* in) {
  if (!in || in->GetNumberOfPoints() == 0)
    throw InputError("the input has no particles");
  const vtkIdType n = in->GetNumberOfPoints();
  vtkPointData* pd = in->GetPointData();
  auto get = [&](const char* name, int components, bool required) -> vtkDataArray* {
    vtkDataArray* a = pd->GetArray(name);
    if (!a) {
      if (required)
        throw InputError(std::string("the input has no point array '") + name + "'");
      return nullptr;
    }
    if (a->GetNumberOfComponents() != components)
      throw InputError(std::string("point array '") + name + "' must have " +
                       std::to_string(components) + " components");
    return a;
  };
  vtkDataArray* radius = get("Radius", 1, true);
  vtkDataArray* mass = get("Mass", 1, false);
  vtkDataArray* density = get("Density", 1, false);
  if (!mass && !density)
    throw InputError("the input needs a 'Mass' or a 'Density' point array");
  vtkDataArray* velocity = get("Velocity", 3, false);
  vtkDataArray* spin = get("AngularVelocity", 3, false);
  vtkDataArray* material = get("Material", 1, false);
  vtkDataArray* id = get("Id", 1, false);
  ParticleSet s;
  s.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double x[3];
    in->GetPoint(i, x);
    const double r = radius->GetTuple1(i);
    const double rho =
        density ? density->GetTuple1(i) : mass->GetTuple1(i) / (4.0 / 3.0 * M_PI * r * r * r);
    s.add(x, r, rho, material ? static_cast<int>(material->GetTuple1(i)) : 0,
          id ? static_cast<std::int64_t>(id->GetTuple1(i)) : static_cast<std::int64_t>(i));
    if (mass)
      s.mass.back() = mass->GetTuple1(i);
    for (int k = 0; k < 3; ++k) {
      s.velocity[3 * i + k] = velocity ? velocity->GetComponent(i, k) : 0.0;
      s.angularVelocity[3 * i + k] = spin ? spin->GetComponent(i, k) : 0.0;
    }
  }
  return s;
}

// The SPH state a hand-off starts from (handoff/Handoff.h's SphSnapshot: x, v, mass, h, not
// included here as sph/SphRun.h has a type of that name too): positions, Velocity, Mass,
// optional SmoothingLength.
template <class SphSnapshot> SphSnapshot sphSnapshotOf(vtkPointSet* in) {
  const vtkIdType n = in->GetNumberOfPoints();
  vtkDataArray* vel = in->GetPointData()->GetArray("Velocity");
  vtkDataArray* mass = in->GetPointData()->GetArray("Mass");
  vtkDataArray* h = in->GetPointData()->GetArray("SmoothingLength");
  if (n == 0)
    throw InputError("the SPH input (port 0) has no particles");
  if (!vel || vel->GetNumberOfComponents() != 3 || !mass)
    throw InputError("the SPH input (port 0) needs point arrays Velocity (3 components) and Mass");
  SphSnapshot s;
  s.x.resize(3 * n), s.v.resize(3 * n), s.mass.resize(n), s.h.assign(n, 0.0);
  for (vtkIdType i = 0; i < n; ++i) {
    in->GetPoint(i, &s.x[3 * i]);
    vel->GetTuple(i, &s.v[3 * i]);
    s.mass[i] = mass->GetComponent(i, 0);
    s.h[i] = h ? h->GetComponent(i, 0) : 0.0;
  }
  return s;
}

inline double fieldScalar(vtkFieldData* fd, const char* name, double fallback) {
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() > 0 ? a->GetComponent(0, 0) : fallback;
}

inline std::string fieldString(vtkFieldData* fd, const char* name) {
  auto* a = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

inline void addField(vtkFieldData* fd, const char* name, double value) {
  fd->RemoveArray(name);
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->InsertNextValue(value);
  fd->AddArray(array);
}

inline void addField(vtkFieldData* fd, const char* name, const double* values, int count) {
  fd->RemoveArray(name);
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(count);
  array->InsertNextTuple(values);
  fd->AddArray(array);
}

inline void addField(vtkFieldData* fd, const char* name, const std::string& value) {
  fd->RemoveArray(name);
  auto array = vtkSmartPointer<vtkStringArray>::New();
  array->SetName(name);
  array->InsertNextValue(value);
  fd->AddArray(array);
}

// One array per value, in order: numbers and vectors as one tuple, series as one number per
// tuple, texts as strings.
inline void addFields(vtkFieldData* fd, const std::vector<NamedValue>& values) {
  for (const NamedValue& v : values) {
    if (v.isText)
      addField(fd, v.name.c_str(), v.text);
    else if (v.isSeries)
      fd->AddArray(doubleArray(v.name.c_str(), 1, v.values));
    else
      addField(fd, v.name.c_str(), v.values.data(), static_cast<int>(v.values.size()));
  }
}

// PrintSelf's "Name: value" lines (the proxy test reads them), from name, value pairs.
inline void printProperties(std::ostream&, vtkIndent) {}
template <class T, class... Rest> void printProperties(std::ostream& os, vtkIndent indent,
                                                       const char* name, const T& value,
                                                       const Rest&... rest) {
  os << indent << name << ": " << value << "\n";
  printProperties(os, indent, rest...);
}

// Progress in [lo, hi] of the algorithm's own range; abort when ParaView asks.
inline ProgressCallback progressOf(vtkAlgorithm* self, double lo = 0.0, double hi = 1.0) {
  return [self, lo, hi](double fraction) {
    self->UpdateProgress(lo + (hi - lo) * fraction);
    return self->GetAbortExecute() == 0;
  };
}

// Runs a solver call; turns its exceptions into a VTK error naming the algorithm.
template <class Call> bool run(vtkAlgorithm* self, Call&& call) {
  try {
    call();
    return true;
  } catch (const InputError& e) {
    vtkErrorWithObjectMacro(self, << "invalid input: " << e.what());
  } catch (const Aborted&) {
    vtkWarningWithObjectMacro(self, << "aborted by the user; the output is empty");
  } catch (const std::bad_alloc&) {
    vtkErrorWithObjectMacro(self, << "out of memory: reduce the problem size");
  } catch (const std::exception& e) {
    vtkErrorWithObjectMacro(self, << "solver failure: " << e.what());
  }
  return false;
}

// A time-dependent algorithm's run: built afresh by BUILD when there is none or when the
// algorithm or its input (STALE) changed since BUILT; false if building failed (reported).
template <class Run, class Build> bool ensureRun(vtkAlgorithm* self, std::unique_ptr<Run>& run,
                                                 vtkTimeStamp& built, bool stale, Build&& build) {
  if (run && !stale && self->GetMTime() <= built)
    return true;
  run.reset();
  if (!bridge::run(self, std::forward<Build>(build)))
    return false;
  built.Modified();
  return true;
}

// Continues RUN from its checkpoint file when the user asked to resume and the file exists.
template <class Run> void resumeIfAsked(Run& run, bool resume, const std::string& file) {
  if (resume && !file.empty() && std::ifstream(file).good())
    run.resumeFrom(file);
}

} // namespace bridge
} // namespace craterkit
