#include "sph/SphCheckpoint.h"

#include "common/CheckpointFormat.h"
#include "common/Error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <vector>

namespace craterkit {

namespace {
const CheckpointKind kSph{"SPH", "SPH checkpoint", {'C', 'K', 'S', 'P', 'H', '1', '\n', '\0'}};

template <class T> void put(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T> void get(std::istream& in, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  if (!in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T))))
    throw InputError("the SPH checkpoint is truncated");
}
} // namespace

void writeSphCheckpoint(const std::string& path, const SphState& s, double time, std::size_t steps,
                        double nextStep) {
  writeCheckpointFile(path, kSph, [&](std::ostream& out) {
    out.write(kSph.legacyMagic, sizeof kSph.legacyMagic);
    const std::uint64_t head[2] = {s.size(), steps};
    out.write(reinterpret_cast<const char*>(head), sizeof head);
    out.write(reinterpret_cast<const char*>(&time), sizeof time);
    out.write(reinterpret_cast<const char*>(&nextStep), sizeof nextStep);
    put(out, s.x), put(out, s.v), put(out, s.mass), put(out, s.rho), put(out, s.u), put(out, s.h);
    put(out, s.S), put(out, s.alpha), put(out, s.damage);
    std::vector<std::int32_t> mat(s.material.begin(), s.material.end());
    put(out, mat);
  });
}

SphState readSphCheckpoint(const std::string& path, double& time, std::size_t& steps,
                           double& nextStep, std::string* warning) {
  SphState s;
  readCheckpointFile(path, kSph, [&](std::istream& in, const CheckpointFrame& frame) {
    const std::uint64_t bytes = frame.payloadBytes;
    char magic[8];
    std::uint64_t head[2];
    if (bytes < 8 || !in.read(magic, sizeof magic) ||
        std::memcmp(magic, kSph.legacyMagic, sizeof magic) != 0)
      throw InputError("not a CraterKit SPH checkpoint (bad magic)");
    if (!in.read(reinterpret_cast<char*>(head), sizeof head) ||
        !in.read(reinterpret_cast<char*>(&time), sizeof time) ||
        !in.read(reinterpret_cast<char*>(&nextStep), sizeof nextStep))
      throw InputError("the SPH checkpoint header is truncated");
    const std::uint64_t n = head[0];
    const std::uint64_t perParticle = 8 * (3 + 3 + 4 + 6 + 2) + 4;
    constexpr std::uint64_t header = 40;
    if (bytes < header || n == 0 || n > (bytes - header) / perParticle ||
        (bytes - header) != n * perParticle)
      throw InputError("the SPH checkpoint's particle count (" + std::to_string(n) +
                       ") does not match its size of " + std::to_string(bytes) + " bytes");
    if (!std::isfinite(time) || !(nextStep > 0.0) || !std::isfinite(nextStep))
      throw InputError("the SPH checkpoint's time or time step is not a finite positive number");
    steps = head[1];
    get(in, s.x, 3 * n), get(in, s.v, 3 * n), get(in, s.mass, n), get(in, s.rho, n);
    get(in, s.u, n), get(in, s.h, n), get(in, s.S, 6 * n), get(in, s.alpha, n);
    get(in, s.damage, n);
    std::vector<std::int32_t> mat;
    get(in, mat, n);
    s.material.assign(mat.begin(), mat.end());
    if (warning)
      *warning = frame.warning;
  });
  return s;
}

} // namespace craterkit
