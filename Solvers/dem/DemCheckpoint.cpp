#include "dem/DemCheckpoint.h"

#include "common/AtomicWrite.h"
#include "common/CheckpointFormat.h"
#include "common/Error.h"
#include "dem/PairList.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

namespace craterkit {

// Checkpoints: the payload of dem/DemCheckpoint.h in the frame of common/CheckpointFormat.h.
// Every count is checked against the bytes left in the payload before anything is allocated.
namespace {

// The payload's magic: CKDEMCP2 with the sparse wall histories, CKDEMCP1 (which a version-1
// file, the payload alone, begins with) with one wall history per particle and wall.
constexpr char kMagic[8] = {'C', 'K', 'D', 'E', 'M', 'C', 'P', '2'};
constexpr char kDenseWallsMagic[8] = {'C', 'K', 'D', 'E', 'M', 'C', 'P', '1'};
const CheckpointKind kDem{"DEM", "DEM checkpoint", {'C', 'K', 'D', 'E', 'M', 'C', 'P', '1'}};

struct Writer {
  std::ostream& out;
  template <class T> void pod(const T& v) {
    out.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint64_t>(s.size());
    out.write(s.data(), static_cast<std::streamsize>(s.size()));
  }
  template <class T> void vec(const std::vector<T>& v) {
    pod<std::uint64_t>(v.size());
    out.write(reinterpret_cast<const char*>(v.data()),
              static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
};

struct Reader {
  std::istream& in;
  std::uint64_t left;
  void need(std::uint64_t bytes, const char* what) {
    if (bytes > left) {
      std::ostringstream msg;
      msg << "checkpoint truncated or corrupt: " << what << " needs " << bytes << " bytes, " << left
          << " left";
      throw InputError(msg.str());
    }
    left -= bytes;
  }
  template <class T> T pod(const char* what) {
    need(sizeof(T), what);
    T v;
    in.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in)
      throw InputError(std::string("checkpoint read failed at ") + what);
    return v;
  }
  std::string str(const char* what) {
    const auto size = pod<std::uint64_t>(what);
    need(size, what);
    std::string s(size, '\0');
    in.read(s.data(), static_cast<std::streamsize>(size));
    return s;
  }
  template <class T> std::vector<T> vec(const char* what, std::uint64_t expected) {
    const auto size = pod<std::uint64_t>(what);
    if (expected != ~0ULL && size != expected) {
      std::ostringstream msg;
      msg << "checkpoint corrupt: " << what << " has " << size << " entries, expected " << expected;
      throw InputError(msg.str());
    }
    if (size > left / sizeof(T)) // before size * sizeof(T), which a crafted count could wrap
      throw InputError(std::string("checkpoint truncated or corrupt: ") + what + " holds " +
                       std::to_string(size) + " entries, more than the bytes left");
    need(size * sizeof(T), what);
    std::vector<T> v(size);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(size * sizeof(T)));
    if (!in)
      throw InputError(std::string("checkpoint read failed at ") + what);
    return v;
  }
};

// The order of (particle, wall) pairs: by particle, then wall.
std::uint64_t wallKey(std::uint32_t particle, std::uint32_t wall) {
  return static_cast<std::uint64_t>(particle) << 32 | wall;
}

// The saved (particle, wall) histories, sorted by particle then wall.
struct SavedWallContacts {
  std::vector<std::uint32_t> particle, wall;
  std::vector<ContactHistory> history;
  std::vector<char> active;
};

SavedWallContacts readWallContacts(Reader& r, std::uint64_t n, std::uint64_t walls, bool dense) {
  SavedWallContacts s;
  if (dense) { // CKDEMCP1: one entry per particle and wall, in that order
    s.history = r.vec<ContactHistory>("wall histories", n * walls);
    s.active = r.vec<char>("wall contacts", n * walls);
    for (std::uint64_t k = 0; k < n * walls; ++k) {
      s.particle.push_back(static_cast<std::uint32_t>(k / walls));
      s.wall.push_back(static_cast<std::uint32_t>(k % walls));
    }
    return s;
  }
  s.particle = r.vec<std::uint32_t>("wall contacts", ~0ULL);
  s.wall = r.vec<std::uint32_t>("wall contacts", s.particle.size());
  s.history = r.vec<ContactHistory>("wall histories", s.particle.size());
  s.active = r.vec<char>("wall contacts", s.particle.size());
  for (std::size_t k = 0; k < s.particle.size(); ++k)
    if (s.particle[k] >= n || s.wall[k] >= walls ||
        (k > 0 && wallKey(s.particle[k - 1], s.wall[k - 1]) >= wallKey(s.particle[k], s.wall[k])))
      throw InputError("checkpoint corrupt: wall contact list out of order");
  return s;
}

} // namespace

void DemSolver::writeCheckpoint(std::ostream& framed) const {
  writeCheckpointFrame(framed, kDem, [this](std::ostream& out) { writeCheckpointPayload(out); });
}

void DemSolver::writeCheckpointPayload(std::ostream& out) const {
  Writer w{out};
  out.write(kMagic, sizeof(kMagic));
  w.pod<std::uint32_t>(1u); // endianness probe
  const ContactParams& c = params_.contact;
  w.str(c.normalModel);
  for (double v : {c.kN, c.kT, c.restitutionN, c.restitutionT, c.muS, c.muR, c.muT, c.beta,
                   c.cohesion, c.youngsModulus, c.poissonRatio})
    w.pod(v);
  w.pod<std::uint64_t>(params_.walls.size());
  for (const Wall& wall : params_.walls) {
    w.pod<std::int32_t>(static_cast<std::int32_t>(wall.type));
    w.pod(wall.point);
    w.pod(wall.normal);
    w.pod(wall.radius);
  }
  w.pod<std::int32_t>(static_cast<std::int32_t>(params_.gravity.type));
  w.pod(params_.gravity.vector);
  w.pod(params_.gravity.GM);
  w.pod(params_.gravity.centre);
  for (double v :
       {params_.dt, params_.skin, params_.overlapWarning, params_.overlapAbort,
        params_.initialOverlapLimit, params_.minStepsPerCollision, params_.warnStepsPerCollision})
    w.pod(v);
  w.pod<std::uint64_t>(n_);
  w.pod(time_);
  w.pod(step_);
  const ParticleSet& s = state_;
  w.vec(s.position);
  w.vec(s.velocity);
  w.vec(s.angularVelocity);
  w.vec(s.radius);
  w.vec(s.mass);
  w.vec(s.density);
  w.vec(s.material);
  w.vec(s.id);
  w.vec(acc_);
  w.vec(alpha_);
  // The contacts as three arrays (first, second, history), each written as it is read from
  // the pair list and the table: no copy of them is held (a snapshot at 10^6 grains).
  const ContactTable& table = tables_[current_];
  const std::uint64_t contacts = static_cast<std::uint64_t>(
      std::count_if(pairs_.active.begin(), pairs_.active.end(), [](char a) { return a != 0; }));
  const auto eachContact = [&](auto item) { // in blocks of 4096, as vec() writes them
    using T = decltype(item(std::size_t{0}));
    std::vector<T> block;
    block.reserve(4096);
    const auto flush = [&] {
      out.write(reinterpret_cast<const char*>(block.data()),
                static_cast<std::streamsize>(block.size() * sizeof(T)));
      block.clear();
    };
    w.pod(contacts);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      if (!pairs_.active[k])
        continue;
      block.push_back(item(k));
      if (block.size() == block.capacity())
        flush();
    }
    flush();
  };
  eachContact([&](std::size_t k) { return pairs_.first[k]; });
  eachContact([&](std::size_t k) { return pairs_.second[k]; });
  eachContact([&](std::size_t k) { return table.historyAt(pairs_.row[k]); });
  // The (particle, wall) pairs within reach, sorted by particle then wall, with their histories
  // and flags.
  w.vec(wallContacts_.particle);
  w.vec(wallContacts_.wall);
  w.vec(wallContacts_.history);
  w.vec(wallContacts_.active);
  w.pod<std::uint64_t>(overlapWarningSteps_);
  out.write(kMagic, sizeof(kMagic)); // trailer: a complete file ends with the magic again
  if (!out)
    throw std::runtime_error("writing the checkpoint failed");
}

std::string DemSolver::checkpointBytes() const {
  return craterkit::checkpointBytes(kDem,
                                    [this](std::ostream& out) { writeCheckpointPayload(out); });
}

DemSolver DemSolver::fromCheckpointBytes(const std::string& bytes) {
  std::unique_ptr<DemSolver> solver;
  readCheckpointBytes(bytes, [&](std::istream& in, std::uint64_t size) {
    solver = std::make_unique<DemSolver>(readCheckpoint(in, size));
  });
  return std::move(*solver);
}

void DemSolver::writeCheckpoint(const std::string& path) const {
  writeFileAtomically(path, "the DEM checkpoint",
                      [this](std::ostream& out) { writeCheckpoint(out); });
}

DemSolver DemSolver::readCheckpoint(std::istream& in, std::uint64_t available) {
  return readCheckpoint(in, available, std::string());
}

DemSolver DemSolver::readCheckpoint(std::istream& in, std::uint64_t framed,
                                    const std::string& source) {
  // The frame and the payload's checksum first, then the payload (all of it, for version 1).
  const CheckpointFrame frame = readCheckpointFrame(in, framed, kDem);
  const std::uint64_t available = frame.payloadBytes;
  Reader r{in, available};
  char magic[8];
  r.need(sizeof(magic), "magic");
  in.read(magic, sizeof(magic));
  const bool denseWalls = in && std::memcmp(magic, kDenseWallsMagic, sizeof(magic)) == 0;
  if (!in || (!denseWalls && std::memcmp(magic, kMagic, sizeof(magic)) != 0))
    throw InputError("not a CraterKit DEM checkpoint (wrong magic)");
  if (r.pod<std::uint32_t>("endianness") != 1u)
    throw InputError("checkpoint written on a machine of the other endianness");
  DemParams p;
  ContactParams& c = p.contact;
  c.normalModel = r.str("normal model");
  for (double* v : {&c.kN, &c.kT, &c.restitutionN, &c.restitutionT, &c.muS, &c.muR, &c.muT, &c.beta,
                    &c.cohesion, &c.youngsModulus, &c.poissonRatio})
    *v = r.pod<double>("contact parameters");
  const auto walls = r.pod<std::uint64_t>("wall count");
  if (walls > 1000)
    throw InputError("checkpoint corrupt: implausible wall count");
  for (std::uint64_t k = 0; k < walls; ++k) {
    Wall wall;
    const auto type = r.pod<std::int32_t>("wall type");
    if (type < 0 || type > static_cast<std::int32_t>(Wall::Type::CylinderAbove))
      throw InputError("checkpoint corrupt: unknown wall type");
    wall.type = static_cast<Wall::Type>(type);
    wall.point = r.pod<std::array<double, 3>>("wall");
    wall.normal = r.pod<std::array<double, 3>>("wall");
    wall.radius = r.pod<double>("wall");
    p.walls.push_back(wall);
  }
  const auto gtype = r.pod<std::int32_t>("gravity type");
  if (gtype < 0 || gtype > 2)
    throw InputError("checkpoint corrupt: unknown gravity type");
  p.gravity.type = static_cast<Gravity::Type>(gtype);
  p.gravity.vector = r.pod<std::array<double, 3>>("gravity");
  p.gravity.GM = r.pod<double>("gravity");
  p.gravity.centre = r.pod<std::array<double, 3>>("gravity");
  for (double* v : {&p.dt, &p.skin, &p.overlapWarning, &p.overlapAbort, &p.initialOverlapLimit,
                    &p.minStepsPerCollision, &p.warnStepsPerCollision})
    *v = r.pod<double>("run parameters");
  const auto n = r.pod<std::uint64_t>("particle count");
  if (n == 0 || n > available / 100)
    throw InputError("checkpoint corrupt: the particle count does not fit the file size");
  const double time = r.pod<double>("time");
  const auto step = r.pod<long long>("step");
  ParticleSet s;
  s.position = r.vec<double>("positions", 3 * n);
  s.velocity = r.vec<double>("velocities", 3 * n);
  s.angularVelocity = r.vec<double>("spins", 3 * n);
  s.radius = r.vec<double>("radii", n);
  s.mass = r.vec<double>("masses", n);
  s.density = r.vec<double>("densities", n);
  s.material = r.vec<int>("materials", n);
  s.id = r.vec<std::int64_t>("ids", n);
  auto acc = r.vec<double>("accelerations", 3 * n);
  auto alpha = r.vec<double>("angular accelerations", 3 * n);
  auto ci = r.vec<std::uint32_t>("contacts", ~0ULL);
  auto cj = r.vec<std::uint32_t>("contacts", ci.size());
  auto ch = r.vec<ContactHistory>("contact histories", ci.size());
  const SavedWallContacts saved = readWallContacts(r, n, walls, denseWalls);
  const auto warnings = r.pod<std::uint64_t>("warning count");
  char trailer[8];
  r.need(sizeof(trailer), "trailer");
  in.read(trailer, sizeof(trailer));
  if (!in || std::memcmp(trailer, magic, sizeof(trailer)) != 0)
    throw InputError(
        "checkpoint incomplete (no trailer): the run was interrupted while writing it");
  for (std::size_t k = 0; k < ci.size(); ++k)
    if (ci[k] >= cj[k] || cj[k] >= n ||
        (k > 0 && ((static_cast<std::uint64_t>(ci[k - 1]) << 32 | cj[k - 1]) >=
                   (static_cast<std::uint64_t>(ci[k]) << 32 | cj[k]))))
      throw InputError("checkpoint corrupt: contact list out of order");

  DemSolver solver(Restore{}, s, p);
  solver.time_ = time;
  solver.step_ = step;
  solver.acc_ = std::move(acc);
  solver.alpha_ = std::move(alpha);
  solver.overlapWarningSteps_ = warnings;
  if (!frame.warning.empty())
    solver.warn(source.empty() ? frame.warning : source + ": " + frame.warning);
  // The wall histories of the walls each particle can reach (a wall it touches is one); both
  // lists are sorted by particle then wall.
  WallContacts& wc = solver.wallContacts_;
  for (std::size_t c = 0, k = 0; c < wc.size(); ++c) {
    const std::uint64_t want = wallKey(wc.particle[c], wc.wall[c]);
    while (k < saved.particle.size() && wallKey(saved.particle[k], saved.wall[k]) < want)
      ++k;
    const bool found =
        k < saved.particle.size() && wallKey(saved.particle[k], saved.wall[k]) == want;
    wc.history[c] = found ? saved.history[k] : ContactHistory{};
    wc.active[c] = found ? saved.active[k] : 0;
  }
  // The saved contacts become the table of the last evaluation, merged into the fresh list
  // (every saved contact must be in it).
  ContactTable& table = solver.tables_[solver.current_];
  table.resize(ci.size());
  const std::size_t found = forCommonPairs(ci, cj, solver.pairs_.first, solver.pairs_.second,
                                           [&](std::size_t a, std::size_t b) {
                                             table.first[a] = ci[a];
                                             table.second[a] = cj[a];
                                             table.setHistory(a, ch[a]);
                                             solver.pairs_.active[b] = 1;
                                             solver.pairs_.row[b] = static_cast<std::uint32_t>(a);
                                           });
  if (found != ci.size())
    throw InputError("checkpoint corrupt: a saved contact is not between neighbouring particles");
  return solver;
}

DemSolver DemSolver::readCheckpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
    throw InputError(path + ": cannot open the DEM checkpoint");
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  try {
    return readCheckpoint(in, size, path);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

DemCheckpointState readDemCheckpointState(const std::string& path) {
  // Read as a restart reads it, so that a file a run would refuse is refused here too.
  const DemSolver solver = DemSolver::readCheckpoint(path);
  return DemCheckpointState{solver.particles(), solver.time(), solver.stepCount(),
                            solver.warnings()};
}

} // namespace craterkit
