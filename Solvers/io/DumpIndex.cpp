#include "io/DumpIndex.h"

#include "io/LammpsDump.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cstring>
#include <memory>
#include <sstream>

namespace craterkit {
namespace dump {

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
void skipLines(Cursor& c, std::size_t n, std::size_t firstLine, const NewlineCensus* census) {
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

} // namespace dump

std::vector<DumpIndexEntry> indexDump(std::string_view text, const std::string& fileName) {
  using namespace dump;
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

} // namespace craterkit
