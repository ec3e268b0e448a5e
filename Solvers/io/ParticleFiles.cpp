#include "io/ParticleFiles.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <cerrno>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

namespace craterkit {

namespace {

// ---- text cursor ------------------------------------------------------------------------------

struct Cursor {
  std::string_view text;
  std::size_t pos = 0;
  std::size_t line = 1; // of the next line to read
  const std::string& file;

  bool atEnd() const { return pos >= text.size(); }
  std::string_view next() {
    if (atEnd())
      fail("unexpected end of file");
    const std::size_t end = text.find('\n', pos);
    std::string_view l =
        text.substr(pos, (end == std::string_view::npos ? text.size() : end) - pos);
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++line;
    if (!l.empty() && l.back() == '\r')
      l.remove_suffix(1);
    return l;
  }
  [[noreturn]] void fail(const std::string& what, std::size_t at = 0) const {
    std::ostringstream s;
    s << file << ":" << (at ? at : line) << ": " << what;
    throw ParseError(s.str());
  }
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  return s;
}

// Splits on blanks into at most `max` tokens (more are reported through `count`).
std::size_t split(std::string_view s, std::string_view* out, std::size_t max) {
  std::size_t n = 0, i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t'))
      ++i;
    if (i >= s.size())
      break;
    const std::size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t')
      ++i;
    if (n < max)
      out[n] = s.substr(start, i - start);
    ++n;
  }
  return n;
}

std::string printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40))
    out += (c >= 32 && c < 127) ? c : '?';
  return out;
}

// LAMMPS's spellings of inf and nan, which from_chars does not read from every writer.
bool special(std::string_view token, double& v) {
  std::string t(token.substr(0, 8));
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (token.size() > 8)
    return false;
  if (t == "nan" || t == "-nan" || t == "+nan")
    v = std::nan("");
  else if (t == "inf" || t == "+inf")
    v = std::numeric_limits<double>::infinity();
  else if (t == "-inf")
    v = -std::numeric_limits<double>::infinity();
  else
    return false;
  return true;
}

double toDouble(std::string_view token, const Cursor& c, std::size_t line, const char* what) {
  double v = 0.0;
  const char* b = token.data();
  const char* e = b + token.size();
  if (!token.empty() && *b == '+')
    ++b;
  const auto r = std::from_chars(b, e, v);
  if ((r.ec != std::errc() || r.ptr != e) && !special(token, v))
    c.fail(std::string("expected a number for ") + what + ", got '" + printable(token) + "'", line);
  return v;
}

// A number read in place ends at a blank, a line end or the end of the text.
bool endsToken(const char* p, const char* end) {
  return p == end || *p == ' ' || *p == '\t' || *p == '\n' || *p == '\r';
}
// The token that starts at p (up to a blank or line end).
std::string_view tokenAt(const char* p, const char* end) {
  const char* q = p;
  while (q < end && *q != ' ' && *q != '\t' && *q != '\n' && *q != '\r')
    ++q;
  return std::string_view(p, static_cast<std::size_t>(q - p));
}

long long toInteger(std::string_view token, const Cursor& c, std::size_t line, const char* what) {
  long long v = 0;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
  if (r.ec != std::errc() || r.ptr != token.data() + token.size())
    c.fail(std::string("expected an integer for ") + what + ", got '" + printable(token) + "'",
           line);
  return v;
}

bool startsWith(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// ---- dump columns -----------------------------------------------------------------------------

enum class Col {
  Id,
  Type,
  X,
  Y,
  Z,
  Xs,
  Ys,
  Zs,
  Vx,
  Vy,
  Vz,
  Wx,
  Wy,
  Wz,
  Radius,
  Diameter,
  Mass,
  Density,
  Extra
};

Col columnKind(std::string_view name) {
  static const std::map<std::string_view, Col> known = {{"id", Col::Id},
                                                        {"type", Col::Type},
                                                        {"x", Col::X},
                                                        {"y", Col::Y},
                                                        {"z", Col::Z},
                                                        {"xu", Col::X},
                                                        {"yu", Col::Y},
                                                        {"zu", Col::Z},
                                                        {"xs", Col::Xs},
                                                        {"ys", Col::Ys},
                                                        {"zs", Col::Zs},
                                                        {"vx", Col::Vx},
                                                        {"vy", Col::Vy},
                                                        {"vz", Col::Vz},
                                                        {"omegax", Col::Wx},
                                                        {"omegay", Col::Wy},
                                                        {"omegaz", Col::Wz},
                                                        {"radius", Col::Radius},
                                                        {"diameter", Col::Diameter},
                                                        {"mass", Col::Mass},
                                                        {"density", Col::Density}};
  const auto it = known.find(name);
  return it == known.end() ? Col::Extra : it->second;
}

} // namespace

// ---- dumps --------------------------------------------------------------------------------------

namespace {
// Reads the header of one snapshot (cursor at its first line); returns the entry and leaves
// the cursor after the ATOMS line. Fills frame if given.
DumpIndexEntry readDumpHeader(Cursor& c, ParticleFrame* frame, std::vector<std::string>* columns) {
  DumpIndexEntry e;
  e.offset = c.pos;
  e.line = c.line;
  bool haveStep = false, haveCount = false, haveTime = false;
  while (true) {
    const std::size_t lineNo = c.line;
    const std::string_view l = trim(c.next());
    if (l.empty() && !haveStep)
      continue;
    if (!startsWith(l, "ITEM:"))
      c.fail("expected an 'ITEM:' line, got '" + printable(l) + "'", lineNo);
    const std::string_view item = trim(l.substr(5));
    if (item == "TIMESTEP") {
      const std::size_t at = c.line;
      e.timestep = toInteger(trim(c.next()), c, at, "TIMESTEP");
      haveStep = true;
    } else if (item == "TIME") {
      const std::size_t at = c.line;
      const double t = toDouble(trim(c.next()), c, at, "TIME");
      e.time = t;
      haveTime = true;
      if (frame)
        frame->time = t;
    } else if (item == "NUMBER OF ATOMS") {
      const std::size_t at = c.line;
      const long long n = toInteger(trim(c.next()), c, at, "NUMBER OF ATOMS");
      if (n < 0)
        c.fail("negative NUMBER OF ATOMS", at);
      e.count = static_cast<std::size_t>(n);
      haveCount = true;
    } else if (startsWith(item, "BOX BOUNDS")) {
      for (int k = 0; k < 3; ++k) {
        const std::size_t at = c.line;
        std::string_view tok[4];
        const std::size_t n = split(c.next(), tok, 4);
        if (n < 2)
          c.fail("a BOX BOUNDS line needs two numbers", at);
        const double lo = toDouble(tok[0], c, at, "BOX BOUNDS"),
                     hi = toDouble(tok[1], c, at, "BOX BOUNDS");
        if (frame) {
          frame->box[2 * k] = lo;
          frame->box[2 * k + 1] = hi;
          frame->hasBox = true;
        }
      }
    } else if (startsWith(item, "ATOMS")) {
      if (!haveStep || !haveCount)
        c.fail("ITEM: ATOMS before TIMESTEP and NUMBER OF ATOMS", lineNo);
      if (!haveTime)
        e.time = static_cast<double>(e.timestep);
      if (columns) {
        columns->clear();
        std::string_view rest = item.substr(5);
        std::vector<std::string_view> tok(1024);
        const std::size_t n = split(rest, tok.data(), tok.size());
        if (n == 0)
          c.fail("ITEM: ATOMS names no columns", lineNo);
        if (n > tok.size())
          c.fail("more than 1024 columns", lineNo);
        for (std::size_t k = 0; k < n; ++k)
          columns->emplace_back(tok[k]);
      }
      return e;
    } else {
      c.fail("unknown item '" + printable(item) + "'", lineNo);
    }
  }
}

// The number of '\n' in [p, e) (memchr: vectorised by the C library, faster than a loop here).
std::size_t countNewlines(const char* p, const char* e) {
  std::size_t n = 0;
  while (p < e) {
    const void* q = std::memchr(p, '\n', static_cast<std::size_t>(e - p));
    if (!q)
      break;
    ++n;
    p = static_cast<const char*>(q) + 1;
  }
  return n;
}

// Newlines per fixed block of a text, counted in parallel, so that the atom lines of a large
// snapshot are skipped a block at a time.
struct NewlineCensus {
  static constexpr std::size_t kBlock = std::size_t(1) << 20;
  std::vector<std::size_t> perBlock;
  explicit NewlineCensus(std::string_view text) : perBlock((text.size() + kBlock - 1) / kBlock) {
    const std::ptrdiff_t blocks = static_cast<std::ptrdiff_t>(perBlock.size());
#pragma omp parallel for schedule(static) if (blocks > 8)
    for (std::ptrdiff_t b = 0; b < blocks; ++b) {
      const std::size_t from = static_cast<std::size_t>(b) * kBlock;
      perBlock[static_cast<std::size_t>(b)] =
          countNewlines(text.data() + from, text.data() + std::min(text.size(), from + kBlock));
    }
  }
};

// Past the n-th line that starts at p (a last line may end at e without '\n'); sets `lines` to
// the number of lines passed (fewer than n only when e came first). With a census of the text
// that starts at `base`, whole blocks are skipped by their counts.
const char* skipLineRange(const char* p, const char* e, std::size_t n, std::size_t& lines,
                          const char* base = nullptr, const NewlineCensus* census = nullptr) {
  lines = 0;
  auto scan = [&](const char* stop) {
    for (; lines < n && p < stop; ++lines) {
      const void* q = std::memchr(p, '\n', static_cast<std::size_t>(stop - p));
      if (!q) {
        if (stop == e)
          p = e, ++lines; // the unterminated last line
        else
          p = stop;
        return;
      }
      p = static_cast<const char*>(q) + 1;
    }
  };
  if (census) {
    const std::size_t kBlock = NewlineCensus::kBlock;
    std::size_t block =
        static_cast<std::size_t>(p - base) / kBlock + 1; // the first whole block after p
    scan(std::min(e, base + block * kBlock));
    while (lines < n && block < census->perBlock.size() && lines + census->perBlock[block] < n &&
           base + (block + 1) * kBlock <= e) {
      lines += census->perBlock[block];
      p = base + (block + 1) * kBlock;
      ++block;
    }
  }
  scan(e);
  return p;
}

// Moves the cursor past n lines (fast: no parsing).
void skipLines(Cursor& c, std::size_t n, std::size_t firstLine,
               const NewlineCensus* census = nullptr) {
  const char* begin = c.text.data();
  std::size_t lines = 0;
  const char* p = skipLineRange(begin + c.pos, begin + c.text.size(), n, lines, begin, census);
  if (lines < n) {
    std::ostringstream s;
    s << "the snapshot starting at line " << firstLine
      << " declares more atoms than the file holds (" << lines << " lines found)";
    c.line += lines;
    c.fail(s.str());
  }
  c.pos = static_cast<std::size_t>(p - begin);
  c.line += n;
}
} // namespace

std::vector<DumpIndexEntry> indexDump(std::string_view text, const std::string& fileName) {
  Cursor c{text, 0, 1, fileName};
  std::vector<DumpIndexEntry> out;
  std::unique_ptr<NewlineCensus> census;
  if (text.size() > 8 * NewlineCensus::kBlock)
    census = std::make_unique<NewlineCensus>(text);
  while (true) {
    // Skip blank lines between snapshots.
    while (!c.atEnd()) {
      const std::size_t save = c.pos, line = c.line;
      if (!trim(c.next()).empty()) {
        c.pos = save;
        c.line = line;
        break;
      }
    }
    if (c.atEnd())
      break;
    DumpIndexEntry e = readDumpHeader(c, nullptr, nullptr);
    // Each atom line needs at least two bytes: refuse counts the file cannot hold before
    // anything is allocated for them.
    if (e.count > (text.size() - c.pos) / 2 + 1)
      c.fail("NUMBER OF ATOMS " + std::to_string(e.count) +
                 " exceeds what the rest of the file can hold",
             e.line);
    skipLines(c, e.count, e.line, census.get());
    e.end = c.pos;
    out.push_back(e);
  }
  if (out.empty())
    throw ParseError(fileName + ": no snapshot (no 'ITEM: TIMESTEP') in the file");
  return out;
}

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

  std::vector<Col> kind(ncol);
  bool has[static_cast<int>(Col::Extra) + 1] = {};
  for (std::size_t k = 0; k < ncol; ++k) {
    kind[k] = columnKind(names[k]);
    if (kind[k] != Col::Extra && has[static_cast<int>(kind[k])])
      c.fail("column '" + names[k] + "' appears twice", e.line);
    has[static_cast<int>(kind[k])] = true;
  }
  const bool scaled = has[static_cast<int>(Col::Xs)] || has[static_cast<int>(Col::Ys)] ||
                      has[static_cast<int>(Col::Zs)];
  for (const auto& [a, b, name] :
       {std::tuple{Col::X, Col::Xs, "x"}, std::tuple{Col::Y, Col::Ys, "y"},
        std::tuple{Col::Z, Col::Zs, "z"}})
    if (!has[static_cast<int>(a)] && !has[static_cast<int>(b)])
      c.fail(std::string("the ATOMS line has no '") + name + "' column (x, xu or xs)", e.line);
  if (scaled && !f.hasBox)
    c.fail("scaled coordinates without BOX BOUNDS", e.line);

  // Extra columns, grouped as vectors when three consecutive names end in x, y, z.
  std::vector<int> extraIndex(ncol, -1), extraComp(ncol, 0);
  for (std::size_t k = 0; k < ncol; ++k) {
    if (kind[k] != Col::Extra || extraIndex[k] >= 0)
      continue;
    const std::string& a = names[k];
    if (k + 2 < ncol && kind[k + 1] == Col::Extra && kind[k + 2] == Col::Extra && a.size() > 1 &&
        a.back() == 'x' && names[k + 1] == a.substr(0, a.size() - 1) + "y" &&
        names[k + 2] == a.substr(0, a.size() - 1) + "z") {
      f.extra.push_back(ExtraArray{a.substr(0, a.size() - 1), 3, {}});
      for (int j = 0; j < 3; ++j) {
        extraIndex[k + j] = static_cast<int>(f.extra.size() - 1);
        extraComp[k + j] = j;
      }
    } else {
      f.extra.push_back(ExtraArray{a, 1, {}});
      extraIndex[k] = static_cast<int>(f.extra.size() - 1);
    }
  }
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
  const bool anyExtra = !f.extra.empty();
#pragma omp parallel for schedule(static, 1) num_threads(pieces)
  for (int t = 0; t < pieces; ++t) {
    const char* p = base + cut[t];
    const char* const end = base + cut[t + 1];
    for (std::size_t i = firstRow[t]; i < firstRow[t + 1]; ++i) {
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
        switch (kk) {
        case Col::X:
          s.position[3 * i] = v;
          break;
        case Col::Y:
          s.position[3 * i + 1] = v;
          break;
        case Col::Z:
          s.position[3 * i + 2] = v;
          break;
        case Col::Xs:
          s.position[3 * i] = f.box[0] + v * (f.box[1] - f.box[0]);
          break;
        case Col::Ys:
          s.position[3 * i + 1] = f.box[2] + v * (f.box[3] - f.box[2]);
          break;
        case Col::Zs:
          s.position[3 * i + 2] = f.box[4] + v * (f.box[5] - f.box[4]);
          break;
        case Col::Vx:
          s.velocity[3 * i] = v;
          break;
        case Col::Vy:
          s.velocity[3 * i + 1] = v;
          break;
        case Col::Vz:
          s.velocity[3 * i + 2] = v;
          break;
        case Col::Wx:
          s.angularVelocity[3 * i] = v;
          break;
        case Col::Wy:
          s.angularVelocity[3 * i + 1] = v;
          break;
        case Col::Wz:
          s.angularVelocity[3 * i + 2] = v;
          break;
        case Col::Radius:
          s.radius[i] = v;
          break;
        case Col::Diameter:
          s.radius[i] = 0.5 * v;
          break;
        case Col::Mass:
          s.mass[i] = v;
          break;
        case Col::Density:
          s.density[i] = v;
          break;
        default:
          if (anyExtra) {
            ExtraArray& x = f.extra[static_cast<std::size_t>(extraIndex[k])];
            x.values[i * x.components + extraComp[k]] = v;
          }
          break;
        }
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

// ---- pkdgrav .ss --------------------------------------------------------------------------------

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

// ---- files
// ------------------------------------------------------------------------------------------

FileBytes::FileBytes(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw ParseError(path + ": cannot open the file");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw ParseError(path + ": not a regular file");
  }
  const std::size_t size = static_cast<std::size_t>(st.st_size);
  if (size > 0) {
    void* m = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (m == MAP_FAILED) {
      ::close(fd);
      throw ParseError(path + ": cannot map the file (" + std::strerror(errno) + ")");
    }
    map_ = static_cast<const char*>(m);
    size_ = size;
  }
  ::close(fd);
  if (size_ >= 2 && static_cast<unsigned char>(map_[0]) == 0x1f &&
      static_cast<unsigned char>(map_[1]) == 0x8b) {
    std::string out;
    try {
      out = gunzip(std::string_view(map_, size_), path);
    } catch (...) {
      ::munmap(const_cast<char*>(map_), size_);
      throw;
    }
    ::munmap(const_cast<char*>(map_), size_);
    map_ = nullptr;
    size_ = 0;
    owned_ = std::move(out);
  }
}

FileBytes::~FileBytes() {
  if (map_)
    ::munmap(const_cast<char*>(map_), size_);
}

std::string readFileBytes(const std::string& path) {
  const FileBytes file(path);
  return std::string(file.view());
}

std::string gunzip(std::string_view raw, const std::string& path) {
  // deflate cannot expand more than about 1032:1, so cap the output there.
  const std::size_t cap = raw.size() * 1032 + (1u << 20);
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK)
    throw ParseError(path + ": cannot initialise zlib");
  std::string out;
  out.resize(std::min<std::size_t>(cap, std::max<std::size_t>(raw.size() * 4, 1 << 16)));
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  z.avail_in =
      static_cast<uInt>(std::min<std::size_t>(raw.size(), std::numeric_limits<uInt>::max()));
  std::size_t produced = 0;
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    if (produced == out.size()) {
      if (out.size() >= cap) {
        inflateEnd(&z);
        throw ParseError(path + ": gzip data expands beyond 1032 times the file size");
      }
      out.resize(std::min(cap, out.size() * 2));
    }
    z.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
    z.avail_out = static_cast<uInt>(
        std::min<std::size_t>(out.size() - produced, std::numeric_limits<uInt>::max()));
    const uInt before = z.avail_out;
    rc = inflate(&z, Z_NO_FLUSH);
    produced += before - z.avail_out;
    if (rc == Z_STREAM_END)
      break;
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::size_t at = z.total_in;
      inflateEnd(&z);
      throw ParseError(path + ": byte " + std::to_string(at) + " of the gzip stream: corrupt data");
    }
    if (rc == Z_BUF_ERROR && z.avail_in == 0) {
      inflateEnd(&z);
      throw ParseError(path + ": truncated gzip stream after " + std::to_string(produced) +
                       " bytes of data");
    }
  }
  inflateEnd(&z);
  out.resize(produced);
  return out;
}

} // namespace craterkit
