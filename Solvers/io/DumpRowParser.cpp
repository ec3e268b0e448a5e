#include "io/DumpColumns.h"
#include "io/DumpIndex.h"
#include "io/DumpText.h"
#include "io/LammpsDump.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

namespace craterkit {

using namespace dump;

namespace {
// Parses the atom lines in [p, end), rows first to last - 1, in place into the frame's arrays
// (sized already). A bad row is reported through fail(row, message), and the next line read.
template <class Fail> void parseDumpRows(const char* p, const char* const end, std::size_t first,
                                         std::size_t last, const DumpColumns& cols,
                                         ParticleFrame& f, Fail&& fail) {
  const std::vector<std::string>& names = cols.names;
  const std::vector<Col>& kind = cols.kind;
  const std::vector<int>& extraIndex = cols.extraIndex;
  const std::vector<int>& extraComp = cols.extraComp;
  const std::size_t ncol = names.size();
  ParticleSet& s = f.particles;
  const bool anyExtra = !f.extra.empty();
  for (std::size_t i = first; i < last; ++i) {
    s.id[i] = static_cast<std::int64_t>(i + 1);
    std::size_t k = 0;
    for (; k < ncol; ++k) {
      while (p < end && (*p == ' ' || *p == '\t'))
        ++p;
      if (p == end || *p == '\n' || *p == '\r')
        break;
      const char* const token = p;
      const Col kk = kind[k];
      if (kk == Col::Id || kk == Col::Type) {
        long long v = 0;
        const auto r = std::from_chars(p, end, v);
        p = r.ptr;
        if (r.ec != std::errc() || !endsToken(p, end)) {
          fail(i, std::string("expected an integer for ") + names[k] + ", got '" +
                      printable(tokenAt(token, end)) + "'");
          break;
        }
        if (kk == Col::Id) {
          s.id[i] = v;
        } else if (v < 1 || v > std::numeric_limits<int>::max()) {
          fail(i, "atom type " + std::to_string(v) + " out of range");
          break;
        } else {
          s.material[i] = static_cast<int>(v - 1);
        }
        continue;
      }
      double v = 0.0;
      const auto r = std::from_chars(p + (*p == '+'), end, v);
      p = r.ptr;
      if (r.ec != std::errc() || !endsToken(p, end)) {
        // from_chars does not read every writer's spelling of inf and nan; accept LAMMPS's.
        const std::string_view t = tokenAt(token, end);
        if (!special(t, v)) {
          fail(i,
               std::string("expected a number for ") + names[k] + ", got '" + printable(t) + "'");
          break;
        }
        p = token + t.size();
      }
      // One column kind a line.
      // clang-format off
      switch (kk) {
      case Col::X: s.position[3 * i] = v; break;
      case Col::Y: s.position[3 * i + 1] = v; break;
      case Col::Z: s.position[3 * i + 2] = v; break;
      case Col::Xs: s.position[3 * i] = f.box[0] + v * (f.box[1] - f.box[0]); break;
      case Col::Ys: s.position[3 * i + 1] = f.box[2] + v * (f.box[3] - f.box[2]); break;
      case Col::Zs: s.position[3 * i + 2] = f.box[4] + v * (f.box[5] - f.box[4]); break;
      case Col::Vx: s.velocity[3 * i] = v; break;
      case Col::Vy: s.velocity[3 * i + 1] = v; break;
      case Col::Vz: s.velocity[3 * i + 2] = v; break;
      case Col::Wx: s.angularVelocity[3 * i] = v; break;
      case Col::Wy: s.angularVelocity[3 * i + 1] = v; break;
      case Col::Wz: s.angularVelocity[3 * i + 2] = v; break;
      case Col::Radius: s.radius[i] = v; break;
      case Col::Diameter: s.radius[i] = 0.5 * v; break;
      case Col::Mass: s.mass[i] = v; break;
      case Col::Density: s.density[i] = v; break;
      default:
        if (anyExtra) {
          ExtraArray& x = f.extra[static_cast<std::size_t>(extraIndex[k])];
          x.values[i * x.components + extraComp[k]] = v;
        }
        break;
      }
      // clang-format on
    }
    // The rest of the line: blanks, then its end; more values are a count mismatch too.
    if (k == ncol) {
      while (p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
        ++p;
      if (p < end && *p != '\n') {
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
        const std::string_view rest(
            p, static_cast<std::size_t>((nl ? static_cast<const char*>(nl) : end) - p));
        fail(i, "expected " + std::to_string(ncol) + " values, found " +
                    std::to_string(ncol + split(rest, nullptr, 0)));
      }
    } else if (p == end || *p == '\n' || *p == '\r') {
      fail(i, "expected " + std::to_string(ncol) + " values, found " + std::to_string(k));
    } // else: the row's bad value was reported
    if (p < end && *p != '\n') {
      const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
      p = nl ? static_cast<const char*>(nl) : end;
    }
    p += p < end; // past the '\n'
  }
}
} // namespace

ParticleFrame parseDumpSnapshot(std::string_view text, const DumpIndexEntry& entry,
                                const std::string& fileName) {
  if (entry.offset > text.size())
    throw ParseError(fileName + ": snapshot offset beyond the end of the file");
  Cursor c{text, entry.offset, entry.line, fileName};
  ParticleFrame f;
  std::vector<std::string> names;
  const DumpIndexEntry e = readDumpHeader(c, &f, &names);
  f.timestep = e.timestep;
  if (f.time == 0.0)
    f.time = static_cast<double>(e.timestep);
  const std::size_t ncol = names.size();
  if (e.count > (text.size() - c.pos) / (2 * ncol) + 1)
    c.fail("NUMBER OF ATOMS " + std::to_string(e.count) +
               " exceeds what the rest of the file can hold",
           e.line);
  const DumpColumns cols = classifyColumns(std::move(names), f, c, e.line);
  const bool* const has = cols.has;
  for (ExtraArray& x : f.extra)
    x.values.assign(e.count * x.components, 0.0);

  const std::size_t n = e.count;
  ParticleSet& s = f.particles;
  s.position.assign(3 * n, 0.0);
  s.velocity.assign(3 * n, 0.0);
  s.angularVelocity.assign(3 * n, 0.0);
  s.radius.assign(n, 0.0);
  s.mass.assign(n, 0.0);
  s.density.assign(n, 0.0);
  s.material.assign(n, 0);
  s.id.resize(n);
  // The rows: the snapshot's bytes are cut into one piece per thread at line ends, the lines
  // of each piece counted (so every row knows its index), then the pieces parsed in place.
  // The first bad row (lowest line) is the one reported, whatever the thread count.
  const std::size_t firstLine = c.line, bodyStart = c.pos;
  std::size_t bodyEnd = entry.end;
  if (bodyEnd < bodyStart || bodyEnd > text.size() || entry.end == 0) {
    skipLines(c, n, e.line); // no usable index end: find it (and report a short file)
    bodyEnd = c.pos;
  }
  const char* const base = text.data();
  std::size_t badRow = n;
  std::string badMessage;
  auto fail = [&](std::size_t row, const std::string& what) {
#pragma omp critical(craterkit_dump_error)
    if (row < badRow) {
      badRow = row;
      std::ostringstream m;
      m << fileName << ":" << firstLine + row << ": " << what;
      badMessage = m.str();
    }
  };
#ifdef _OPENMP
  const int pieces = n >= 20000 ? std::max(1, omp_get_max_threads()) : 1;
#else
  const int pieces = 1; // the fuzzing build has no OpenMP
#endif
  std::vector<std::size_t> cut(static_cast<std::size_t>(pieces) + 1, bodyEnd),
      firstRow(static_cast<std::size_t>(pieces) + 1, 0);
  cut[0] = bodyStart;
  for (int t = 1; t < pieces; ++t) {
    const std::size_t at =
        std::max(cut[t - 1], bodyStart + (bodyEnd - bodyStart) * static_cast<std::size_t>(t) /
                                             static_cast<std::size_t>(pieces));
    const void* nl = at < bodyEnd ? std::memchr(base + at, '\n', bodyEnd - at) : nullptr;
    cut[t] = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - base) + 1 : bodyEnd;
  }
#pragma omp parallel for schedule(static, 1) num_threads(pieces)
  for (int t = 0; t < pieces; ++t) {
    const char* p = base + cut[t];
    const char* q = base + cut[t + 1];
    std::size_t lines = countNewlines(p, q);
    if (q > p && q[-1] != '\n')
      ++lines; // the unterminated last line of the file
    firstRow[t + 1] = lines;
  }
  for (int t = 0; t < pieces; ++t)
    firstRow[t + 1] += firstRow[t];
  if (firstRow[pieces] != n) {
    // The index entry does not describe these bytes (the file changed since it was indexed).
    Cursor again{text, bodyStart, firstLine, fileName};
    skipLines(again, n, e.line);
    c.fail("the snapshot's atom lines end elsewhere than its index says; index the file again",
           e.line);
  }
#pragma omp parallel for schedule(static, 1) num_threads(pieces)
  for (int t = 0; t < pieces; ++t)
    parseDumpRows(base + cut[t], base + cut[t + 1], firstRow[t], firstRow[t + 1], cols, f, fail);
  if (badRow < n)
    throw ParseError(badMessage);
  f.hasVelocity = has[static_cast<int>(Col::Vx)] || has[static_cast<int>(Col::Vy)] ||
                  has[static_cast<int>(Col::Vz)];
  f.hasAngularVelocity = has[static_cast<int>(Col::Wx)] || has[static_cast<int>(Col::Wy)] ||
                         has[static_cast<int>(Col::Wz)];
  f.hasRadius = has[static_cast<int>(Col::Radius)] || has[static_cast<int>(Col::Diameter)];
  f.hasMass = has[static_cast<int>(Col::Mass)];
  f.hasDensity = has[static_cast<int>(Col::Density)];
  f.hasMaterial = has[static_cast<int>(Col::Type)];
  f.hasId = has[static_cast<int>(Col::Id)];
  if (f.hasMass && f.hasRadius && !f.hasDensity) {
    for (std::size_t i = 0; i < n; ++i)
      s.density[i] = s.radius[i] > 0.0
                         ? s.mass[i] / (4.0 / 3.0 * M_PI * s.radius[i] * s.radius[i] * s.radius[i])
                         : 0.0;
    f.hasDensity = true;
  }
  return f;
}

} // namespace craterkit
