#include "io/LammpsDump.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

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

namespace {
// A snapshot's columns: what each one holds, which kinds are present, and where each extra
// column goes (its array in the frame's extra arrays and its component there).
struct DumpColumns {
  std::vector<std::string> names;
  std::vector<Col> kind;
  bool has[static_cast<int>(Col::Extra) + 1] = {};
  std::vector<int> extraIndex, extraComp;
};

// Classifies the ATOMS line's columns and checks them (no kind twice, x, y and z present, a
// box for scaled coordinates); adds the frame's extra arrays (no values yet), grouped as
// vectors when three consecutive names end in x, y, z. Errors name the header's line.
DumpColumns classifyColumns(std::vector<std::string> names, ParticleFrame& f, const Cursor& c,
                            std::size_t headerLine) {
  DumpColumns cols;
  cols.names = std::move(names);
  const std::vector<std::string>& n = cols.names;
  const std::size_t ncol = n.size();
  std::vector<Col>& kind = cols.kind;
  bool* const has = cols.has;
  kind.resize(ncol);
  for (std::size_t k = 0; k < ncol; ++k) {
    kind[k] = columnKind(n[k]);
    if (kind[k] != Col::Extra && has[static_cast<int>(kind[k])])
      c.fail("column '" + n[k] + "' appears twice", headerLine);
    has[static_cast<int>(kind[k])] = true;
  }
  const bool scaled = has[static_cast<int>(Col::Xs)] || has[static_cast<int>(Col::Ys)] ||
                      has[static_cast<int>(Col::Zs)];
  for (const auto& [a, b, name] :
       {std::tuple{Col::X, Col::Xs, "x"}, std::tuple{Col::Y, Col::Ys, "y"},
        std::tuple{Col::Z, Col::Zs, "z"}})
    if (!has[static_cast<int>(a)] && !has[static_cast<int>(b)])
      c.fail(std::string("the ATOMS line has no '") + name + "' column (x, xu or xs)", headerLine);
  if (scaled && !f.hasBox)
    c.fail("scaled coordinates without BOX BOUNDS", headerLine);

  std::vector<int>& extraIndex = cols.extraIndex;
  std::vector<int>& extraComp = cols.extraComp;
  extraIndex.assign(ncol, -1);
  extraComp.assign(ncol, 0);
  for (std::size_t k = 0; k < ncol; ++k) {
    if (kind[k] != Col::Extra || extraIndex[k] >= 0)
      continue;
    const std::string& a = n[k];
    if (k + 2 < ncol && kind[k + 1] == Col::Extra && kind[k + 2] == Col::Extra && a.size() > 1 &&
        a.back() == 'x' && n[k + 1] == a.substr(0, a.size() - 1) + "y" &&
        n[k + 2] == a.substr(0, a.size() - 1) + "z") {
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
  return cols;
}

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
