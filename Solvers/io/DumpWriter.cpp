#include "io/LammpsDump.h"

#include <algorithm>
#include <charconv>
#include <string>

namespace craterkit {

std::string writeDump(const ParticleFrame& frame) {
  const ParticleSet& s = frame.particles;
  const std::size_t n = s.size();
  std::string out;
  out.reserve(64 + n * 300);
  char buf[64];
  auto num = [&](double v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, v); // shortest exact representation
    out.append(buf, r.ptr);
  };
  out += "ITEM: TIME\n";
  num(frame.time);
  out += "\nITEM: TIMESTEP\n" + std::to_string(frame.timestep < 0 ? 0 : frame.timestep) + "\n";
  out += "ITEM: NUMBER OF ATOMS\n" + std::to_string(n) + "\n";
  double box[6] = {0, 0, 0, 0, 0, 0};
  if (frame.hasBox) {
    std::copy(frame.box, frame.box + 6, box);
  } else if (n) {
    for (int k = 0; k < 3; ++k) {
      box[2 * k] = box[2 * k + 1] = s.position[k];
      for (std::size_t i = 0; i < n; ++i) {
        box[2 * k] = std::min(box[2 * k], s.position[3 * i + k] - s.radius[i]);
        box[2 * k + 1] = std::max(box[2 * k + 1], s.position[3 * i + k] + s.radius[i]);
      }
    }
  }
  out += "ITEM: BOX BOUNDS ff ff ff\n";
  for (int k = 0; k < 3; ++k) {
    num(box[2 * k]);
    out += ' ';
    num(box[2 * k + 1]);
    out += '\n';
  }
  out += "ITEM: ATOMS id type x y z vx vy vz omegax omegay omegaz radius mass";
  for (const ExtraArray& x : frame.extra) {
    if (x.components == 3)
      out += " " + x.name + "x " + x.name + "y " + x.name + "z";
    else
      for (int k = 0; k < x.components; ++k)
        out += " " + x.name + (x.components > 1 ? "_" + std::to_string(k) : std::string());
  }
  out += '\n';
  for (std::size_t i = 0; i < n; ++i) {
    out += std::to_string(s.id[i]);
    out += ' ';
    out += std::to_string(s.material[i] + 1);
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      num(s.position[3 * i + k]);
    }
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      num(s.velocity[3 * i + k]);
    }
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      num(s.angularVelocity[3 * i + k]);
    }
    out += ' ';
    num(s.radius[i]);
    out += ' ';
    num(s.mass[i]);
    for (const ExtraArray& x : frame.extra)
      for (int k = 0; k < x.components; ++k) {
        out += ' ';
        num(x.values[i * x.components + k]);
      }
    out += '\n';
  }
  return out;
}

} // namespace craterkit
