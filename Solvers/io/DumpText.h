// The text of a LAMMPS dump (LammpsDump.h): a line cursor that names the file and line in its
// errors, and the blank-separated tokens and numbers of a line, read in place. Shared by the
// dump index, the column classification and the row parser.
#pragma once

#include "io/ParticleFrame.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>

namespace craterkit {
namespace dump {

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

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  return s;
}

// Splits on blanks into at most `max` tokens (more are reported through `count`).
inline std::size_t split(std::string_view s, std::string_view* out, std::size_t max) {
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

inline std::string printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40))
    out += (c >= 32 && c < 127) ? c : '?';
  return out;
}

// LAMMPS's spellings of inf and nan, which from_chars does not read from every writer.
inline bool special(std::string_view token, double& v) {
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

inline double toDouble(std::string_view token, const Cursor& c, std::size_t line,
                       const char* what) {
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
inline bool endsToken(const char* p, const char* end) {
  return p == end || *p == ' ' || *p == '\t' || *p == '\n' || *p == '\r';
}
// The token that starts at p (up to a blank or line end).
inline std::string_view tokenAt(const char* p, const char* end) {
  const char* q = p;
  while (q < end && *q != ' ' && *q != '\t' && *q != '\n' && *q != '\r')
    ++q;
  return std::string_view(p, static_cast<std::size_t>(q - p));
}

inline long long toInteger(std::string_view token, const Cursor& c, std::size_t line,
                           const char* what) {
  long long v = 0;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
  if (r.ec != std::errc() || r.ptr != token.data() + token.size())
    c.fail(std::string("expected an integer for ") + what + ", got '" + printable(token) + "'",
           line);
  return v;
}

inline bool startsWith(std::string_view s, std::string_view p) {
  return s.substr(0, p.size()) == p;
}

} // namespace dump
} // namespace craterkit
