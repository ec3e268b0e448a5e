#include "edmd/HardDiskReport.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

HardDiskPoints hardDiskPoints(const HardDiskCraterRun& run) {
  const HardDisks& d = run.system().disks();
  HardDiskPoints o;
  o.xyz.resize(3 * d.size()), o.velocity.resize(3 * d.size()), o.density.resize(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    o.xyz[3 * i] = d.x[i], o.xyz[3 * i + 1] = 0.0, o.xyz[3 * i + 2] = d.y[i];
    o.velocity[3 * i] = d.vx[i], o.velocity[3 * i + 1] = 0.0, o.velocity[3 * i + 2] = d.vy[i];
    o.density[i] = d.mass[i] / (M_PI * d.radius[i] * d.radius[i]);
  }
  o.tracer.assign(d.size(), 0);
  for (std::uint32_t k : run.tracers())
    o.tracer[k] = 1;
  const std::vector<char>& touched = run.system().disturbed();
  o.disturbed.assign(touched.begin(), touched.end());
  return o;
}

HardDiskLines hardDiskTracerPaths(const HardDiskCraterRun& run) {
  HardDiskLines o;
  for (std::size_t k = 0; k < run.tracers().size(); ++k) {
    const std::vector<double>& path = run.tracerPaths()[k];
    const std::size_t count = path.size() / 2;
    o.counts.push_back(count);
    for (std::size_t f = 0; f < count; ++f) {
      o.xyz.insert(o.xyz.end(), {path[2 * f], 0.0, path[2 * f + 1]});
      o.time.push_back(run.frameTime(f));
    }
    o.ids.push_back(run.system().disks().id[run.tracers()[k]]);
  }
  return o;
}

HardDiskLines hardDiskOutline(const HardDiskCraterRun& run) {
  const double bin = 4.0 * std::max(run.params().diskRadius, run.params().maxDiskRadius);
  const std::vector<double> top = run.surfaceProfile(bin);
  HardDiskLines o;
  o.counts.push_back(top.size());
  for (std::size_t b = 0; b < top.size(); ++b)
    o.xyz.insert(o.xyz.end(), {(b + 0.5) * bin, 0.0, top[b]});
  o.crater =
      measureSection(top, bin, run.impactX(), run.surfaceLevel(), 2.0 * run.params().diskRadius);
  return o;
}

std::vector<NamedValue> hardDiskFields(const HardDiskCraterRun& run, const SectionCrater& crater) {
  const HardDiskSystem& system = run.system();
  const HardDisks& d = system.disks();
  const std::vector<HardDiskCraterRun::Ejection> ejections = run.ejections();
  const double meanAngle = HardDiskCraterRun::meanEjectionAngle(ejections);
  double px, py;
  system.momentum(px, py);
  auto series = [&](const char* name, double HardDiskCraterRun::Ejection::*member) {
    std::vector<double> values(ejections.size());
    for (std::size_t k = 0; k < ejections.size(); ++k)
      values[k] = ejections[k].*member;
    return NamedValue::series(name, std::move(values));
  };
  using V = NamedValue;
  return {V::number("Time", run.frameTime(run.currentFrame())),
          V::number("Frame", static_cast<double>(run.currentFrame())),
          V::number("PairCollisions", static_cast<double>(system.pairCollisions())),
          V::number("WallCollisions", static_cast<double>(system.wallCollisions())),
          V::number("KineticEnergy", system.kineticEnergy()),
          V::vector("TotalMomentum", {px, 0.0, py}),
          V::number("ShockFrontRadius", run.shockFront().back()),
          V::vector("ImpactPoint", {run.impactX(), 0.0, run.surfaceLevel()}),
          V::number("SurfaceHeight", run.surfaceLevel()),
          V::vector("BoxSize", {system.params().width, 0.0, system.params().height}),
          V::number("EjectedDisks", static_cast<double>(ejections.size())),
          V::number("MeanEjectionAngle", meanAngle),
          V::number("CraterDepth", crater.depth),
          V::number("CraterWidth", crater.width),
          series("EjectionAngle", &HardDiskCraterRun::Ejection::angleDeg),
          series("EjectionDistance", &HardDiskCraterRun::Ejection::distance),
          series("EjectionSpeed", &HardDiskCraterRun::Ejection::speed),
          series("EjectionTime", &HardDiskCraterRun::Ejection::time),
          V::series("ShockFrontHistory", run.shockFront()),
          V::number("GroundDisks",
                    static_cast<double>(std::count(d.material.begin(), d.material.end(), 0)))};
}

} // namespace craterkit
