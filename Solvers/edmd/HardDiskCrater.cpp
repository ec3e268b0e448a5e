#include "edmd/HardDiskCrater.h"

#include "common/Error.h"
#include "common/Random.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace craterkit {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kJamming =
    0.82; // above this, monodisperse and narrow-range disks jam or crystallise

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void require(bool ok, const std::string& message) {
  if (!ok)
    throw InputError(message);
}
} // namespace

void HardDiskCraterParams::validate() const {
  auto finite = [](double v) { return std::isfinite(v); };
  require(finite(width) && width > 0.0, "Width must be positive (got " + num(width) + ")");
  require(finite(groundDepth) && groundDepth > 0.0,
          "GroundDepth must be positive (got " + num(groundDepth) + ")");
  require(finite(diskRadius) && diskRadius > 0.0,
          "DiskRadius must be positive (got " + num(diskRadius) + ")");
  require(finite(maxDiskRadius) && (maxDiskRadius == 0.0 || maxDiskRadius >= diskRadius),
          "MaxDiskRadius must be 0 (one size) or at least DiskRadius (got " + num(maxDiskRadius) +
              ")");
  const double rmax = std::max(diskRadius, maxDiskRadius);
  require(2.0 * rmax < width && 2.0 * rmax < groundDepth,
          "a disk (diameter " + num(2.0 * rmax) + " m) is larger than the box or the ground layer");
  require(finite(areaFraction) && areaFraction > 0.0,
          "AreaFraction must be positive (got " + num(areaFraction) + ")");
  require(areaFraction <= kJamming, "AreaFraction " + num(areaFraction) +
                                        " is above the jamming limit of random disk packings (" +
                                        num(kJamming) + ")");
  require(finite(groundDensity) && groundDensity > 0.0,
          "GroundDensity must be positive (got " + num(groundDensity) + ")");
  require(finite(impactorRadius) && impactorRadius > 0.0,
          "ImpactorRadius must be positive (got " + num(impactorRadius) + ")");
  require(impactor != Impactor::Clump || impactorRadius >= diskRadius,
          "a clump impactor must be at least one disk radius wide");
  require(finite(densityRatio) && densityRatio > 0.0,
          "DensityRatio must be positive (got " + num(densityRatio) + ")");
  require(finite(impactSpeed) && impactSpeed >= 0.0,
          "ImpactSpeed must be zero or positive (got " + num(impactSpeed) + ")");
  require(finite(impactAngle) && impactAngle >= 0.0 && impactAngle < 90.0,
          "ImpactAngle must be in [0, 90) degrees from the vertical (got " + num(impactAngle) +
              ")");
  require(finite(headroom) && headroom >= 2.0 * impactorRadius + rmax,
          "Headroom must fit the impactor above the ground (at least " +
              num(2.0 * impactorRadius + rmax) + " m)");
  require(
      0.5 * width - (impactorRadius + 0.5 * diskRadius) * std::tan(impactAngle * kPi / 180.0) >=
          impactorRadius,
      "the impactor starts outside the box at this ImpactAngle: widen the box or lower the angle");
  require(finite(restitution) && restitution > 0.0 && restitution <= 1.0,
          "Restitution must be in (0, 1] (got " + num(restitution) + ")");
  require(finite(gravity) && gravity >= 0.0,
          "Gravity must be zero or positive (got " + num(gravity) + ")");
  require(finite(frameInterval) && frameInterval > 0.0,
          "FrameInterval must be positive (got " + num(frameInterval) + ")");
  require(finite(endTime) && endTime >= 0.0,
          "EndTime must be zero or positive (got " + num(endTime) + ")");
  require(endTime / frameInterval <= 1e5, "more than 100000 frames: raise FrameInterval");
  require(finite(tracerFraction) && tracerFraction >= 0.0 && tracerFraction <= 1.0,
          "TracerFraction must be in [0, 1] (got " + num(tracerFraction) + ")");
  const double meanArea = kPi * (diskRadius * diskRadius + diskRadius * rmax + rmax * rmax) / 3.0;
  require(areaFraction * width * groundDepth / meanArea <= 2e7,
          "the ground would need more than 2e7 disks: raise DiskRadius or shrink the box");
}

std::vector<std::string> HardDiskCraterParams::presetNames() {
  return {"Ball pit", "Dense sand", "Clump impactor"};
}

HardDiskCraterParams HardDiskCraterParams::preset(const std::string& name) {
  HardDiskCraterParams p;
  if (name == "Ball pit")
    return p; // the seed's model: elastic, one size, a dense single impactor, no gravity
  if (name == "Dense sand") {
    p.maxDiskRadius = 0.0075;
    p.areaFraction = 0.80;
    p.restitution = 0.8;
    p.densityRatio = 2.5;
    p.impactSpeed = 20.0;
    return p;
  }
  if (name == "Clump impactor") {
    p.impactor = Impactor::Clump;
    p.impactorRadius = 0.04;
    p.impactAngle = 30.0;
    return p;
  }
  throw InputError("unknown preset '" + name + "' (Ball pit, Dense sand, Clump impactor)");
}

HardDisks generateHardDiskGround(const HardDiskCraterParams& p, const ProgressCallback& progress) {
  p.validate();
  Random rng(p.seed);
  const double rmin = p.diskRadius, rmax = std::max(p.diskRadius, p.maxDiskRadius);
  const double W = p.width, D = p.groundDepth;
  // Radii until the requested area is filled, placed largest first.
  std::vector<double> radii;
  double area = 0.0;
  while (area < p.areaFraction * W * D) {
    const double r = rmax > rmin ? rng.uniform(rmin, rmax) : rmin;
    radii.push_back(r);
    area += kPi * r * r;
  }
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  const double phi = area / (W * D);
  const double phi0 = std::min(phi, 0.40), shrink = std::sqrt(phi0 / phi);

  // Random sequential addition of the shrunken disks on a grid of buckets.
  const double cell = 2.0 * rmax * shrink;
  const std::size_t nx = std::max<std::size_t>(1, static_cast<std::size_t>(W / cell));
  const std::size_t ny = std::max<std::size_t>(1, static_cast<std::size_t>(D / cell));
  std::vector<std::vector<std::uint32_t>> bucket(nx * ny);
  HardDisks g;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    const double r = radii[k] * shrink;
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      const double x = rng.uniform(r, W - r), y = rng.uniform(r, D - r);
      const long cx = std::min<long>(static_cast<long>(nx) - 1, static_cast<long>(x / (W / nx)));
      const long cy = std::min<long>(static_cast<long>(ny) - 1, static_cast<long>(y / (D / ny)));
      bool free = true;
      for (long by = std::max(0L, cy - 1); free && by <= std::min<long>(ny - 1, cy + 1); ++by)
        for (long bx = std::max(0L, cx - 1); free && bx <= std::min<long>(nx - 1, cx + 1); ++bx)
          for (std::uint32_t j : bucket[by * nx + bx]) {
            const double dx = g.x[j] - x, dy = g.y[j] - y, s = g.radius[j] + r;
            if (dx * dx + dy * dy < s * s) {
              free = false;
              break;
            }
          }
      if (free) {
        bucket[cy * nx + cx].push_back(static_cast<std::uint32_t>(g.size()));
        g.add(x, y, 0.0, 0.0, r, 1.0, kGround, static_cast<std::int64_t>(g.size()));
        placed = true;
      }
    }
    if (!placed)
      throw InputError("random placement failed at area fraction " + num(phi0) +
                       ": enlarge the box");
    if (k % 4096 == 0)
      reportProgress(progress, 0.2 * k / radii.size());
  }

  if (phi > phi0) {
    // Lubachevsky–Stillinger: random velocities of unit rms speed, radii growing at 5 % of
    // it, temperature reset twenty times along the way.
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double a = 2.0 * kPi * rng.uniform();
      g.vx[i] = std::cos(a);
      g.vy[i] = std::sin(a);
    }
    HardDiskParams hp;
    hp.width = W;
    hp.height = D;
    hp.growthRate = 0.05 / (2.0 * rmin * shrink);
    hp.growthEnd = (1.0 / shrink - 1.0) / hp.growthRate;
    HardDiskSystem sys(g, hp);
    const int chunks = 20;
    for (int c = 1; c <= chunks; ++c) {
      sys.advanceTo(hp.growthEnd * c / chunks);
      const double ke = sys.kineticEnergy() / sys.disks().size();
      if (ke > 0.0)
        sys.scaleVelocities(std::sqrt(0.5 / ke));
      if (sys.pairCollisions() > 20000 * g.size())
        throw InputError("the compression to area fraction " + num(phi) +
                         " stalled (the disks jammed): lower AreaFraction");
      reportProgress(progress, 0.2 + 0.8 * c / chunks);
    }
    g = sys.disks();
  }
  for (std::size_t i = 0; i < g.size(); ++i) {
    g.radius[i] = radii[i];
    g.vx[i] = g.vy[i] = 0.0;
    g.mass[i] = p.groundDensity * kPi * radii[i] * radii[i];
  }
  return g;
}

HardDiskCraterRun::HardDiskCraterRun(const HardDiskCraterParams& p,
                                     const ProgressCallback& progress)
    : p_(p) {
  HardDisks d = generateHardDiskGround(p_, progress);
  const std::size_t ground = d.size();
  const double rmin = p_.diskRadius, R = p_.impactorRadius;
  const double th = p_.impactAngle * kPi / 180.0;
  const double dirX = std::sin(th), dirY = -std::cos(th);
  const double gap = 0.5 * rmin;
  const double cx = impactX() - (R + gap) * std::tan(th), cy = p_.groundDepth + R + gap;
  const double rhoI = p_.densityRatio * p_.groundDensity;
  const double vx = p_.impactSpeed * dirX, vy = p_.impactSpeed * dirY;
  if (p_.impactor == HardDiskCraterParams::Impactor::Disk) {
    d.add(cx, cy, vx, vy, R, rhoI * kPi * R * R, kImpactor, static_cast<std::int64_t>(ground));
  } else {
    // Hexagonal clump of ground-sized disks filling the impactor disk.
    const double s = 2.0 * rmin * (1.0 + 1e-9), reach = R - rmin;
    const int rows = static_cast<int>(std::ceil(reach / (s * std::sqrt(3.0) / 2.0)));
    for (int row = -rows; row <= rows; ++row) {
      const double y = row * s * std::sqrt(3.0) / 2.0;
      const double shift = (row & 1) ? 0.5 * s : 0.0;
      const int cols = static_cast<int>(std::ceil(reach / s)) + 1;
      for (int col = -cols; col <= cols; ++col) {
        const double x = col * s + shift;
        if (x * x + y * y <= reach * reach + 1e-12)
          d.add(cx + x, cy + y, vx, vy, rmin, rhoI * kPi * rmin * rmin, kImpactor,
                static_cast<std::int64_t>(d.size()));
      }
    }
  }
  HardDiskParams hp;
  hp.width = p_.width;
  hp.height = p_.groundDepth + p_.headroom;
  hp.restitution = hp.wallRestitution = p_.restitution;
  hp.gravity = p_.gravity;
  // TC model: collisions closer together than the time to cross 1 % of a radius at the impact
  // speed are elastic (guards inelastic collapse).
  if (p_.restitution < 1.0)
    hp.tcTime = 0.01 * rmin / std::max(p_.impactSpeed, 1e-3);
  system_ = std::make_unique<HardDiskSystem>(d, hp);
  system_->watchSurface(p_.groundDepth, kGround);
  system_->trackDisturbance(kImpactor);
  frames_ = static_cast<std::size_t>(std::floor(p_.endTime / p_.frameInterval * (1.0 + 1e-12))) + 1;
  Random pick(p_.seed ^ 0x9e3779b97f4a7c15ULL);
  for (std::size_t i = 0; i < ground; ++i)
    if (pick.uniform() < p_.tracerFraction)
      tracers_.push_back(static_cast<std::uint32_t>(i));
  paths_.assign(tracers_.size(), {});
  recordFrame();
}

double HardDiskCraterRun::frameTime(std::size_t k) const {
  return static_cast<double>(k) * p_.frameInterval;
}

void HardDiskCraterRun::advanceToFrame(std::size_t k, const ProgressCallback& progress) {
  if (k >= frames_)
    throw InputError("frame " + std::to_string(k) + " is beyond the last frame (" +
                     std::to_string(frames_ - 1) + ")");
  if (k < current_)
    throw InputError("a hard-disk run only goes forwards: start a new run for an earlier frame");
  const std::size_t first = current_;
  while (current_ < k) {
    const double done = static_cast<double>(current_ - first) / static_cast<double>(k - first);
    const double share = 1.0 / static_cast<double>(k - first);
    system_->advanceTo(frameTime(current_ + 1),
                       [&](double f) { return !progress || progress(done + share * f); });
    ++current_;
    recordFrame();
    reportProgress(progress,
                   static_cast<double>(current_ - first) / static_cast<double>(k - first));
  }
}

void HardDiskCraterRun::recordFrame() {
  const HardDisks& d = system_->disks();
  for (std::size_t t = 0; t < tracers_.size(); ++t) {
    paths_[t].push_back(d.x[tracers_[t]]);
    paths_[t].push_back(d.y[tracers_[t]]);
  }
  double front = 0.0;
  const std::vector<char>& hit = system_->disturbed();
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d.material[i] == kGround && hit[i])
      front = std::max(front, std::hypot(d.x[i] - impactX(), d.y[i] - surfaceLevel()));
  // The front is the farthest the disturbance has reached so far.
  shock_.push_back(shock_.empty() ? front : std::max(front, shock_.back()));
}

std::vector<HardDiskCraterRun::Ejection> HardDiskCraterRun::ejections() const {
  std::vector<Ejection> out;
  for (const SurfaceCrossing& c : system_->surfaceCrossings()) {
    Ejection e;
    e.angleDeg = std::atan2(c.vy, std::abs(c.vx)) * 180.0 / kPi;
    e.distance = std::abs(c.x - impactX());
    e.speed = std::hypot(c.vx, c.vy);
    e.time = c.time;
    out.push_back(e);
  }
  return out;
}

double HardDiskCraterRun::meanEjectionAngle(const std::vector<Ejection>& ejections) {
  if (ejections.empty())
    return std::nan("");
  double mean = 0.0;
  for (const auto& e : ejections)
    mean += e.angleDeg;
  mean /= ejections.size();
  return mean;
}

std::vector<double> hardDiskFrameTimes(double frameInterval, double endTime) {
  std::vector<double> times{0.0};
  if (frameInterval > 0.0 && endTime > 0.0 && std::isfinite(endTime / frameInterval)) {
    const long frames = static_cast<long>(std::floor(endTime / frameInterval * (1.0 + 1e-12)));
    for (long k = 1; k <= std::min(frames, 100000L); ++k)
      times.push_back(k * frameInterval);
  }
  return times;
}

std::vector<double> HardDiskCraterRun::surfaceProfile(double bin) const {
  if (!(bin > 0.0))
    throw InputError("the profile bin width must be positive");
  const HardDisks& d = system_->disks();
  const std::size_t nb = static_cast<std::size_t>(std::ceil(p_.width / bin));
  std::vector<std::vector<std::pair<double, double>>> col(nb);
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d.material[i] == kGround) {
      const std::size_t b = std::min(nb - 1, static_cast<std::size_t>(std::max(0.0, d.x[i]) / bin));
      col[b].emplace_back(d.y[i], d.radius[i]);
    }
  const double gapLimit = 4.0 * std::max(p_.diskRadius, p_.maxDiskRadius);
  std::vector<double> top(nb, 0.0);
  for (std::size_t b = 0; b < nb; ++b) {
    std::sort(col[b].begin(), col[b].end());
    double last = -1.0;
    for (const auto& yr : col[b]) {
      if (last >= 0.0 && yr.first - last > gapLimit)
        break;
      last = yr.first;
      top[b] = yr.first + yr.second;
    }
  }
  return top;
}

} // namespace craterkit
