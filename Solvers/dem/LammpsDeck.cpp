// LAMMPS data file and input deck from a CraterKit DEM state: see LammpsDeck.h.
#include "dem/LammpsDeck.h"

#include "common/AtomicWrite.h"
#include "common/Error.h"
#include "common/LammpsNumber.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace craterkit {

void checkLammpsOutputTimes(const std::vector<double>& times, double dt, const std::string& what) {
  if (times.empty())
    throw InputError(what + ": no output times");
  long long last = 0;
  for (double t : times) {
    const long long n = std::llround(t / dt);
    if (!(t > 0.0) || !std::isfinite(t) || n <= last)
      throw InputError(what + ": output time " + lammpsNumber(t) +
                       " s is not after the previous one by at least one step (dt " +
                       lammpsNumber(dt) + " s)");
    last = n;
  }
}

void checkLammpsFileName(const std::string& name, const std::string& what) {
  if (name.empty() || name.find_first_of("/ \t\n'\"") != std::string::npos)
    throw InputError(what + ": bad file name '" + name + "'");
}

namespace {

std::string num(double v) { return lammpsNumber(v); }

// Reference values for the coefficients LAMMPS cannot vary per pair: the median grain.
struct Median {
  double radius, mass;
};
Median medianGrain(const ParticleSet& p) {
  std::vector<std::size_t> order(p.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  const auto mid = order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2);
  std::nth_element(order.begin(), mid, order.end(),
                   [&](std::size_t a, std::size_t b) { return p.radius[a] < p.radius[b]; });
  return {p.radius[*mid], p.mass[*mid]};
}

bool axisAligned(const std::array<double, 3>& n, int& axis, double& sign) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(n[k]) - 1.0) < 1e-12 && std::abs(n[(k + 1) % 3]) < 1e-12 &&
        std::abs(n[(k + 2) % 3]) < 1e-12) {
      axis = k;
      sign = n[k] > 0 ? 1.0 : -1.0;
      return true;
    }
  return false;
}

const char* kAxis = "xyz";

} // namespace

double tsujiAlpha(double e) {
  // Tsuji, Tanaka & Ishida (1992, Powder Technol. 71:239) fit, as LAMMPS' `damping tsuji`.
  return 1.2728 - 4.2783 * e + 11.087 * e * e - 22.348 * std::pow(e, 3) + 27.467 * std::pow(e, 4) -
         18.022 * std::pow(e, 5) + 4.8218 * std::pow(e, 6);
}

double tsujiRestitutionFor(double alpha) {
  // α(e) falls monotonically from 1.2728 at e = 0 to ~3e-4 at e = 1: bisection.
  if (!(alpha >= tsujiAlpha(1.0) && alpha <= tsujiAlpha(0.0)))
    throw InputError("LAMMPS deck: the damping ratio " + num(alpha) +
                     " lies outside the range of LAMMPS' Tsuji damping [" + num(tsujiAlpha(1.0)) +
                     ", " + num(tsujiAlpha(0.0)) + "] (normal restitution too low)");
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tsujiAlpha(mid) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::string LammpsCoefficients::pairCoeff() const {
  std::string s = (hertz ? "hertz " : "hooke ") + num(kN) + " " + num(dampingRestitution);
  s += (hertz ? " tangential mindlin " : " tangential linear_history ") + num(kT) + " " +
       num(xGammaT) + " " + num(muS);
  if (muRoll > 0.0)
    s += " rolling sds " + num(kRoll) + " " + num(gammaRoll) + " " + num(muRoll);
  if (muTwist > 0.0)
    s += " twisting sds " + num(kTwist) + " " + num(gammaTwist) + " " + num(muTwist);
  return s + " damping tsuji limit_damping";
}

LammpsCoefficients lammpsCoefficients(const ContactParams& c, const ParticleSet& p, bool wall) {
  c.validate();
  if (c.cohesion != 0.0)
    throw InputError("LAMMPS deck: cohesion " + num(c.cohesion) +
                     " Pa has no `pair_style granular` counterpart (only JKR/DMT); set it to 0");
  if (p.size() == 0)
    throw InputError("LAMMPS deck: no particles");
  const Median g = medianGrain(p);
  // Reduced radius and mass of the reference contact: two median grains, or one and a wall.
  const double rStar = wall ? g.radius : 0.5 * g.radius, mStar = wall ? g.mass : 0.5 * g.mass;
  LammpsCoefficients k;
  k.hertz = c.normalModel == "Hertz";
  const NormalLawKind kind = k.hertz ? NormalLawKind::Hertz : NormalLawKind::LinearSpringDashpot;
  const double f = clippedDampingFactor(kind, c.restitutionN), fT = dashpotFactor(c.restitutionT);
  double kN, cN, kT, cT; // CraterKit's stiffnesses and dashpots at the reference contact
  if (k.hertz) {
    const double nu = c.poissonRatio;
    const double eStar = c.youngsModulus / ((wall ? 1.0 : 2.0) * (1 - nu * nu));
    // Reference overlap for the overlap-dependent rolling and twisting stiffnesses: 1 %
    // of the reduced radius (DEMIntegrator's default MaxOverlap).
    const double a = std::sqrt(rStar * 0.01 * rStar);
    const double ratio = 2.0 * (1.0 - nu) / (2.0 - nu);
    k.kN = 4.0 / 3.0 * eStar;
    k.dampingRestitution = tsujiRestitutionFor(f * std::sqrt(1.5));
    k.kT = ratio * 2.0 * eStar;
    k.xGammaT = fT * std::sqrt(ratio * 2.0) / (f * std::sqrt(1.5) * std::sqrt(4.0 / 3.0));
    kN = 2.0 * eStar * a;
    kT = ratio * kN;
    cN = f * std::sqrt(kN * mStar);
  } else {
    kN = c.kN;
    kT = c.tangentialStiffness();
    cN = f * std::sqrt(kN * mStar);
    k.kN = kN;
    k.dampingRestitution = tsujiRestitutionFor(f);
    k.kT = kT;
    k.xGammaT = fT * std::sqrt(kT) / (f * std::sqrt(kN));
  }
  cT = fT * std::sqrt(kT * mStar);
  k.muS = c.muS;
  const double b = c.beta, br = b * rStar;
  k.kRoll = kN * b * b;
  k.gammaRoll = cN * b * b;
  k.muRoll = c.muR * b;
  k.kTwist = 2.0 * kT * br * br;
  k.gammaTwist = 2.0 * cT * br * br;
  k.muTwist = c.muT * br * c.muS;
  return k;
}

void LammpsDeckParams::validate() const {
  dem.validate();
  if (!(dem.dt > 0.0))
    throw InputError("LAMMPS deck: the time step must be > 0, got " + num(dem.dt));
  if (dem.gravity.type == Gravity::Type::PointMass)
    throw InputError("LAMMPS deck: point-mass gravity has no `fix gravity` counterpart");
  checkLammpsOutputTimes(outputTimes, dem.dt, "LAMMPS deck");
  for (const std::string& name : {dataFile, inputFile, dumpFile})
    checkLammpsFileName(name, "LAMMPS deck");
}

std::string lammpsDataFile(const ParticleSet& p, const LammpsDeckParams& params) {
  const std::size_t n = p.size();
  if (n == 0)
    throw InputError("LAMMPS deck: no particles");
  int types = 1;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -lo[k];
  }
  std::vector<std::int64_t> ids(p.id);
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end())
    throw InputError("LAMMPS deck: duplicate Id " +
                     std::to_string(*std::adjacent_find(ids.begin(), ids.end())));
  if (ids.front() < 0 || ids.back() >= std::numeric_limits<std::int32_t>::max())
    throw InputError("LAMMPS deck: Id " +
                     std::to_string(ids.front() < 0 ? ids.front() : ids.back()) +
                     " does not fit LAMMPS' 32-bit atom ids (atom id = Id + 1)");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(p.radius[i] > 0.0) || !(p.mass[i] > 0.0))
      throw InputError("LAMMPS deck: particle Id " + std::to_string(p.id[i]) + " has radius " +
                       num(p.radius[i]) + " and mass " + num(p.mass[i]));
    if (p.material[i] < 0)
      throw InputError("LAMMPS deck: particle Id " + std::to_string(p.id[i]) + " has material " +
                       std::to_string(p.material[i]));
    types = std::max(types, p.material[i] + 1);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p.position[3 * i + k] - p.radius[i]);
      hi[k] = std::max(hi[k], p.position[3 * i + k] + p.radius[i]);
    }
  }
  std::string s = "CraterKit DEM state at t = " + num(params.startTime) +
                  " s (atom_style sphere; atom id = CraterKit Id + 1)\n\n";
  s += std::to_string(n) + " atoms\n" + std::to_string(types) + " atom types\n\n";
  for (int k = 0; k < 3; ++k) {
    // The deck's boundary is shrink-wrapped (m): this box only has to hold the atoms.
    const double pad = 0.01 * (hi[k] - lo[k]) + 1e-9 * (std::abs(lo[k]) + std::abs(hi[k]) + 1.0);
    s += num(lo[k] - pad) + " " + num(hi[k] + pad) + " " + kAxis[k] + "lo " + kAxis[k] + "hi\n";
  }
  s += "\nAtoms # sphere\n\n";
  for (std::size_t i = 0; i < n; ++i) {
    // Density from the mass, so that LAMMPS' mass (4π/3 r³ ρ) is CraterKit's to rounding.
    const double rho = p.mass[i] / (4.0 / 3.0 * M_PI * std::pow(p.radius[i], 3));
    s += std::to_string(p.id[i] + 1) + " " + std::to_string(p.material[i] + 1) + " " +
         num(2.0 * p.radius[i]) + " " + num(rho);
    for (int k = 0; k < 3; ++k)
      s += " " + num(p.position[3 * i + k]);
    s += "\n";
  }
  s += "\nVelocities\n\n";
  for (std::size_t i = 0; i < n; ++i) {
    s += std::to_string(p.id[i] + 1);
    for (int k = 0; k < 3; ++k)
      s += " " + num(p.velocity[3 * i + k]);
    for (int k = 0; k < 3; ++k)
      s += " " + num(p.angularVelocity[3 * i + k]);
    s += "\n";
  }
  return s;
}

namespace {

// The `fix wall/gran` and `fix wall/gran/region` commands (and their regions) for the walls.
std::string wallCommands(const std::vector<Wall>& walls, const std::string& model) {
  std::ostringstream s;
  // A cylinder matching a bowl's rim is part of the bowl's region (see below).
  std::vector<char> absorbed(walls.size(), 0);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& b = walls[w];
    if (b.type != Wall::Type::Bowl)
      continue;
    for (std::size_t c = 0; c < walls.size(); ++c) {
      const Wall& y = walls[c];
      if ((y.type == Wall::Type::Cylinder || y.type == Wall::Type::CylinderAbove) &&
          y.radius == b.radius && y.point[0] == b.point[0] && y.point[1] == b.point[1] &&
          std::abs(y.normal[2]) == 1.0)
        absorbed[c] = 1;
    }
  }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& wall = walls[w];
    const std::string id = "wall" + std::to_string(w + 1);
    int axis = 0;
    double sign = 1.0;
    if (absorbed[w])
      continue;
    switch (wall.type) {
    case Wall::Type::Plane:
      if (axisAligned(wall.normal, axis, sign)) {
        const std::string at = num(wall.point[static_cast<std::size_t>(axis)]);
        s << "fix " << id << " all wall/gran granular " << model << " " << kAxis[axis] << "plane "
          << (sign > 0 ? at + " NULL" : "NULL " + at) << "\n";
      } else {
        s << "region " << id << "r plane " << num(wall.point[0]) << " " << num(wall.point[1]) << " "
          << num(wall.point[2]) << " " << num(wall.normal[0]) << " " << num(wall.normal[1]) << " "
          << num(wall.normal[2]) << " side in units box\n";
        s << "fix " << id << " all wall/gran/region granular " << model << " region " << id
          << "r\n";
      }
      break;
    case Wall::Type::Cylinder:
    case Wall::Type::CylinderAbove: {
      if (!axisAligned(wall.normal, axis, sign))
        throw InputError("LAMMPS deck: wall " + std::to_string(w + 1) +
                         " is a cylinder whose axis is not along x, y or z");
      const std::size_t a = static_cast<std::size_t>(axis);
      // CylinderAbove acts only beyond its axis point along its axis.
      const std::string from = num(wall.point[a]);
      const std::string span = wall.type == Wall::Type::Cylinder ? "-INF INF"
                               : sign > 0                        ? from + " INF"
                                                                 : "-INF " + from;
      s << "region " << id << "r cylinder " << kAxis[axis] << " " << num(wall.point[(a + 1) % 3])
        << " " << num(wall.point[(a + 2) % 3]) << " " << num(wall.radius) << " " << span
        << " side in units box\n";
      s << "fix " << id << " all wall/gran/region granular " << model << " region " << id << "r\n";
      break;
    }
    case Wall::Type::Bowl: {
      if (!(wall.normal[0] == 0.0 && wall.normal[1] == 0.0 && wall.normal[2] == 1.0))
        throw InputError("LAMMPS deck: wall " + std::to_string(w + 1) +
                         " is a bowl whose up direction is not +z");
      // The inside of the sphere's lower half and of the cylinder above the rim: the union's
      // surface has no upper hemisphere and no cap at the rim.
      const std::string c = num(wall.point[0]) + " " + num(wall.point[1]);
      s << "region " << id << "s sphere " << c << " " << num(wall.point[2]) << " "
        << num(wall.radius) << " side in units box\n";
      s << "region " << id << "c cylinder z " << c << " " << num(wall.radius) << " "
        << num(wall.point[2]) << " INF side in units box\n";
      s << "region " << id << "r union 2 " << id << "s " << id << "c side in units box\n";
      s << "fix " << id << " all wall/gran/region granular " << model << " region " << id << "r\n";
      break;
    }
    case Wall::Type::Disk:
      throw InputError("LAMMPS deck: wall " + std::to_string(w + 1) +
                       " is a disk, which LAMMPS' granular walls cannot represent");
    }
  }
  return s.str();
}

} // namespace

std::string lammpsInputDeck(const ParticleSet& p, const LammpsDeckParams& params) {
  params.validate();
  const DemParams& d = params.dem;
  const LammpsCoefficients pair = lammpsCoefficients(d.contact, p, false);
  const LammpsCoefficients wall = lammpsCoefficients(d.contact, p, true);
  double rmin = p.radius[0];
  for (double r : p.radius)
    rmin = std::min(rmin, r);
  const double skin = d.skin >= 0.0 ? d.skin : 0.2 * rmin;
  std::ostringstream s;
  s << "# CraterKit DEM stage for LAMMPS (written by CraterKit's LammpsDeck).\n"
       "# Needs LAMMPS 29 Oct 2020 or later (pair_style granular with limit_damping and\n"
       "# damping tsuji) built with the GRANULAR package; tested with 29 Sep 2021.\n"
       "# Run: mpirun -np N lmp -in "
    << params.inputFile
    << "   (scripts/run-lammps)\n"
       "# Contact law: pkdgrav SSDEM mapped term by term (Solvers/dem/LammpsDeck.h,\n"
       "# docs/lammps.md).\n"
       "# Atom id = CraterKit Id + 1. Times in the dump count from the state's time "
    << num(params.startTime) << " s.\n"
    << "units si\natom_style sphere\nboundary m m m\nnewton off\ncomm_modify vel yes\n"
    << "read_data " << params.dataFile << "\n"
    << "neighbor " << num(skin) << " bin\nneigh_modify delay 0 every 1 check yes\n"
    << "pair_style granular\npair_coeff * * " << pair.pairCoeff() << "\n";
  s << wallCommands(d.walls, wall.pairCoeff());
  if (d.gravity.type == Gravity::Type::Uniform) {
    const auto& g = d.gravity.vector;
    const double gm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (gm > 0.0)
      s << "fix gravity all gravity " << num(gm) << " vector " << num(g[0] / gm) << " "
        << num(g[1] / gm) << " " << num(g[2] / gm) << "\n";
  }
  s << "fix integrate all nve/sphere\n"
    << "timestep " << num(d.dt) << "\n"
    << "thermo_style custom step time atoms ke\nthermo_modify lost ignore norm no\n"
    << "thermo " << std::max<long long>(1, std::llround(params.outputTimes.back() / d.dt) / 20)
    << "\n";
  const std::string dump = "write_dump all custom " + params.dumpFile +
                           " id type x y z vx vy vz omegax omegay omegaz radius mass"
                           " modify format float %.17g time yes append yes\n";
  long long done = 0;
  for (double t : params.outputTimes) {
    const long long n = std::llround(t / d.dt);
    s << "run " << (n - done) << (done > 0 ? " pre no post no" : "") << "\n" << dump;
    done = n;
  }
  return s.str();
}

void writeLammpsDeck(const std::string& dir, const ParticleSet& particles,
                     const LammpsDeckParams& params) {
  const std::string input = lammpsInputDeck(particles, params);
  const std::string data = lammpsDataFile(particles, params);
  std::filesystem::create_directories(dir);
  writeFileAtomically(dir + "/" + params.dataFile, "LAMMPS data file",
                      [&](std::ostream& out) { out << data; });
  writeFileAtomically(dir + "/" + params.inputFile, "LAMMPS input deck",
                      [&](std::ostream& out) { out << input; });
}

namespace {

// Next non-blank line of a data file, with its comment stripped; false at the end.
struct DataLines {
  std::string_view text;
  std::size_t pos = 0, line = 0;
  bool next(std::string& out) {
    while (pos < text.size()) {
      const std::size_t end = std::min(text.find('\n', pos), text.size());
      std::string_view l = text.substr(pos, end - pos);
      pos = end + 1;
      ++line;
      l = l.substr(0, std::min(l.find('#'), l.size()));
      if (l.find_first_not_of(" \t\r") == std::string_view::npos)
        continue;
      out.assign(l);
      return true;
    }
    return false;
  }
};

} // namespace

ParticleSet parseLammpsData(std::string_view text, const std::string& fileName) {
  DataLines in{text};
  std::string l;
  long long atoms = -1;
  in.next(l); // the title line is free text, even if it looks like a header line
  auto fail = [&](const std::string& what) -> InputError {
    return InputError(fileName + ":" + std::to_string(in.line) + ": " + what);
  };
  // Header: counts and box; the first section keyword ends it.
  while (in.next(l) && l.find("Atoms") != 0) {
    std::istringstream h(l);
    long long v;
    std::string word;
    if ((h >> v >> word) && word == "atoms")
      atoms = v;
  }
  if (atoms < 0 || atoms > static_cast<long long>(text.size() / 8))
    throw fail("no 'N atoms' header line before the Atoms section");
  const std::size_t n = static_cast<std::size_t>(atoms);
  ParticleSet p;
  p.reserve(n);
  std::vector<std::int64_t> atomId(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!in.next(l))
      throw fail("the Atoms section ends after " + std::to_string(i) + " of " + std::to_string(n));
    std::istringstream a(l);
    long long id, type;
    double d, rho, x[3];
    if (!(a >> id >> type >> d >> rho >> x[0] >> x[1] >> x[2]) || id < 1 || type < 1 || !(d > 0))
      throw fail("expected 'id type diameter density x y z'");
    // Strings to double with the stream are exact (correctly rounded): %.17g comes back.
    p.add(x, 0.5 * d, rho, static_cast<int>(type - 1), id - 1);
    p.mass.back() = 4.0 * M_PI / 3.0 * std::pow(0.5 * d, 3) * rho;
    atomId[i] = id;
  }
  if (!in.next(l) || l.find("Velocities") != 0)
    return p; // no Velocities section: at rest
  std::vector<std::size_t> index(n);
  for (std::size_t i = 0; i < n; ++i)
    index[i] = i;
  std::sort(index.begin(), index.end(),
            [&](std::size_t a, std::size_t b) { return atomId[a] < atomId[b]; });
  for (std::size_t i = 0; i < n; ++i) {
    if (!in.next(l))
      throw fail("the Velocities section ends after " + std::to_string(i) + " of " +
                 std::to_string(n));
    std::istringstream v(l);
    long long id;
    double u[6];
    if (!(v >> id >> u[0] >> u[1] >> u[2] >> u[3] >> u[4] >> u[5]))
      throw fail("expected 'id vx vy vz wx wy wz'");
    const auto it = std::lower_bound(index.begin(), index.end(), id,
                                     [&](std::size_t a, long long b) { return atomId[a] < b; });
    if (it == index.end() || atomId[*it] != id)
      throw fail("velocity of unknown atom " + std::to_string(id));
    for (int k = 0; k < 3; ++k) {
      p.velocity[3 * *it + k] = u[k];
      p.angularVelocity[3 * *it + k] = u[3 + k];
    }
  }
  return p;
}

} // namespace craterkit
