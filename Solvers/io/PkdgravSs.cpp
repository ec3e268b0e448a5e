#include "io/PkdgravSs.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace craterkit {

double PkdgravUnits::time() {
  constexpr double G = 6.67430e-11; // CODATA 2018
  return std::sqrt(length * length * length / (G * mass));
}

namespace {
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the .ss byte swapping assumes a little-endian host");
std::uint64_t loadBE64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return __builtin_bswap64(v); // XDR is big-endian; the targets here are little-endian
}
std::uint32_t loadBE32(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return __builtin_bswap32(v);
}
double loadDouble(const unsigned char* p) {
  const std::uint64_t bits = loadBE64(p);
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}
std::int32_t loadInt(const unsigned char* p) {
  const std::uint32_t u = loadBE32(p);
  std::int32_t v;
  std::memcpy(&v, &u, 4);
  return v;
}
void storeDouble(std::string& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  for (int k = 7; k >= 0; --k)
    out += static_cast<char>((bits >> (8 * k)) & 0xFF);
}
void storeInt(std::string& out, std::int32_t v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  for (int k = 3; k >= 0; --k)
    out += static_cast<char>((u >> (8 * k)) & 0xFF);
}
std::int32_t byteSwapped(std::int32_t v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  u = (u >> 24) | ((u >> 8) & 0xFF00) | ((u << 8) & 0xFF0000) | (u << 24);
  std::int32_t r;
  std::memcpy(&r, &u, 4);
  return r;
}
constexpr std::size_t kSsHeader = 16, kSsParticle = 96;
constexpr std::int32_t kMagicStandard = -1, kMagicReduced = -10101;
} // namespace

ParticleFrame parseSs(std::string_view bytes, const std::string& fileName, bool scaleToSI) {
  auto fail = [&](std::size_t offset, const std::string& what) -> void {
    throw ParseError(fileName + ": byte " + std::to_string(offset) + ": " + what);
  };
  if (bytes.size() < kSsHeader)
    fail(0, "truncated header (" + std::to_string(bytes.size()) + " bytes, a .ss header has 16)");
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const double time = loadDouble(p);
  const std::int32_t n = loadInt(p + 8), magic = loadInt(p + 12);
  if (magic == kMagicReduced)
    fail(12, "the reduced .ss format (magic -10101) is not supported; write the standard format");
  if (magic != kMagicStandard) {
    if (byteSwapped(magic) == kMagicStandard || byteSwapped(magic) == kMagicReduced)
      fail(12, "little-endian .ss file: pkdgrav writes XDR (big-endian)");
    fail(12,
         "wrong magic number " + std::to_string(magic) + " (expected -1): not a pkdgrav .ss file");
  }
  // A little-endian file (not XDR) shows itself by a count that fits the size only swapped.
  const std::int32_t swapped = byteSwapped(n);
  if (swapped >= 0 && swapped != n &&
      bytes.size() == kSsHeader + kSsParticle * static_cast<std::size_t>(swapped))
    fail(8, "little-endian .ss file: pkdgrav writes XDR (big-endian)");
  if (n < 0)
    fail(8, "negative particle count " + std::to_string(n));
  const std::size_t need = kSsHeader + kSsParticle * static_cast<std::size_t>(n);
  if (bytes.size() < need)
    fail(8, "the header declares " + std::to_string(n) + " particles (" + std::to_string(need) +
                " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
  if (bytes.size() > need)
    fail(need, std::to_string(bytes.size() - need) + " unexpected bytes after the last particle");
  const double L = scaleToSI ? PkdgravUnits::length : 1.0, M = scaleToSI ? PkdgravUnits::mass : 1.0,
               T = scaleToSI ? PkdgravUnits::time() : 1.0;
  ParticleFrame f;
  f.time = time * T;
  ParticleSet& s = f.particles;
  const std::size_t count = static_cast<std::size_t>(n);
  s.position.resize(3 * count);
  s.velocity.resize(3 * count);
  s.angularVelocity.resize(3 * count);
  s.radius.resize(count);
  s.mass.resize(count);
  s.density.resize(count);
  s.material.assign(count, 0);
  s.id.resize(count);
  ExtraArray color{"Color", 1, std::vector<double>(count)};
#pragma omp parallel for schedule(static) if (count >= 20000)
  for (std::size_t i = 0; i < count; ++i) {
    const unsigned char* q = p + kSsHeader + kSsParticle * i;
    s.mass[i] = loadDouble(q) * M;
    s.radius[i] = loadDouble(q + 8) * L;
    for (int k = 0; k < 3; ++k) {
      s.position[3 * i + k] = loadDouble(q + 16 + 8 * k) * L;
      s.velocity[3 * i + k] = loadDouble(q + 40 + 8 * k) * (L / T);
      s.angularVelocity[3 * i + k] = loadDouble(q + 64 + 8 * k) / T;
    }
    color.values[i] = loadInt(q + 88);
    s.id[i] = loadInt(q + 92);
    const double r = s.radius[i];
    s.density[i] = r > 0.0 ? s.mass[i] / (4.0 / 3.0 * M_PI * r * r * r) : 0.0;
  }
  f.extra.push_back(std::move(color));
  f.hasVelocity = f.hasAngularVelocity = f.hasRadius = f.hasMass = f.hasDensity = f.hasId = true;
  return f;
}

std::string writeSs(const ParticleFrame& frame, bool scaleFromSI) {
  const ParticleSet& s = frame.particles;
  const std::size_t n = s.size();
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()) / kSsParticle)
    throw InputError("too many particles for a .ss file (" + std::to_string(n) + ")");
  const double L = scaleFromSI ? PkdgravUnits::length : 1.0,
               M = scaleFromSI ? PkdgravUnits::mass : 1.0,
               T = scaleFromSI ? PkdgravUnits::time() : 1.0;
  const ExtraArray* color = nullptr;
  for (const ExtraArray& x : frame.extra)
    if (x.name == "Color" && x.components == 1 && x.values.size() == n)
      color = &x;
  std::string out;
  out.reserve(kSsHeader + kSsParticle * n);
  storeDouble(out, frame.time / T);
  storeInt(out, static_cast<std::int32_t>(n));
  storeInt(out, kMagicStandard);
  for (std::size_t i = 0; i < n; ++i) {
    if (s.id[i] < std::numeric_limits<std::int32_t>::min() ||
        s.id[i] > std::numeric_limits<std::int32_t>::max())
      throw InputError("particle Id " + std::to_string(s.id[i]) +
                       " does not fit the .ss original index (32 bits)");
    storeDouble(out, s.mass[i] / M);
    storeDouble(out, s.radius[i] / L);
    for (int k = 0; k < 3; ++k)
      storeDouble(out, s.position[3 * i + k] / L);
    for (int k = 0; k < 3; ++k)
      storeDouble(out, s.velocity[3 * i + k] / (L / T));
    for (int k = 0; k < 3; ++k)
      storeDouble(out, s.angularVelocity[3 * i + k] * T);
    // pkdgrav colours: keep the file's, else 3 (green) for material 0, 4, 5, ... for the rest.
    storeInt(out, color ? static_cast<std::int32_t>(color->values[i]) : 3 + s.material[i]);
    storeInt(out, static_cast<std::int32_t>(s.id[i]));
  }
  return out;
}

} // namespace craterkit
