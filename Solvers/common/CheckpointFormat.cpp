#include "common/CheckpointFormat.h"

#include "common/AtomicWrite.h"
#include "common/Error.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <vector>

#include <zlib.h>

namespace craterkit {
namespace {

constexpr char kMagic[8] = {'C', 'R', 'A', 'T', 'E', 'R', 'K', 'T'};
// Offsets in the header (CheckpointFormat.h).
constexpr std::size_t kVersionAt = 8, kHeaderSizeAt = 12, kKindAt = 16, kWriterAt = 24,
                      kPayloadSizeAt = 56, kPayloadCrcAt = 64, kHeaderCrcAt = 68;
constexpr std::size_t kKindBytes = 8, kWriterBytes = 32;
using Header = std::array<unsigned char, kCheckpointHeaderBytes>;

void putLe(Header& h, std::size_t at, std::uint64_t v, std::size_t bytes) {
  for (std::size_t k = 0; k < bytes; ++k)
    h[at + k] = static_cast<unsigned char>(v >> (8 * k));
}
std::uint64_t getLe(const Header& h, std::size_t at, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < bytes; ++k)
    v |= static_cast<std::uint64_t>(h[at + k]) << (8 * k);
  return v;
}
void putText(Header& h, std::size_t at, std::size_t bytes, const std::string& text) {
  std::fill(h.begin() + at, h.begin() + at + bytes, 0);
  std::memcpy(h.data() + at, text.data(), std::min(bytes, text.size()));
}
std::string getText(const Header& h, std::size_t at, std::size_t bytes) {
  const char* p = reinterpret_cast<const char*>(h.data() + at);
  return std::string(p, std::find(p, p + bytes, '\0'));
}

// Passes what is written on to another stream buffer and keeps the CRC-32 and count of it.
class CrcBuffer : public std::streambuf {
public:
  explicit CrcBuffer(std::streambuf* to) : to_(to) {}
  std::uint32_t crc = 0;
  std::uint64_t bytes = 0;

protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof()))
      return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const std::streamsize written = to_->sputn(s, n);
    if (written > 0) {
      crc = checkpointCrc32(s, static_cast<std::uint64_t>(written), crc);
      bytes += static_cast<std::uint64_t>(written);
    }
    return written;
  }

private:
  std::streambuf* to_;
};

// Counts what is written, and keeps none of it.
class CountingBuffer : public std::streambuf {
public:
  std::uint64_t bytes = 0;

protected:
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof()))
      ++bytes;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += static_cast<std::uint64_t>(n);
    return n;
  }
};

// Reads and writes a fixed block of memory in place, with seeks within it (the frame's writer
// goes back to fill in its header; its reader goes back to the payload). Writing past the end
// fails.
class SpanBuffer : public std::streambuf {
public:
  SpanBuffer(char* begin, std::size_t size) {
    setg(begin, begin, begin + size);
    setp(begin, begin + size);
  }

protected:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                   std::ios_base::openmode which) override {
    const bool out = (which & std::ios_base::out) != 0;
    char* base = out ? pbase() : eback();
    char* end = out ? epptr() : egptr();
    char* now = out ? pptr() : gptr();
    const off_type from = dir == std::ios_base::beg   ? 0
                          : dir == std::ios_base::cur ? now - base
                                                      : end - base;
    const off_type to = from + off;
    if (to < 0 || to > end - base)
      return pos_type(off_type(-1));
    if (out) {
      setp(base, end);
      for (off_type left = to; left > 0;) { // pbump takes an int
        const int step = static_cast<int>(std::min<off_type>(left, 1 << 30));
        pbump(step);
        left -= step;
      }
    } else {
      setg(base, base + to, end);
    }
    return pos_type(to);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }
};

std::string sizeText(std::uint64_t bytes) {
  return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
}

} // namespace

std::uint32_t checkpointCrc32(const void* data, std::uint64_t bytes, std::uint32_t crc) {
  const auto* p = static_cast<const Bytef*>(data);
  uLong c = crc;
  while (bytes > 0) {
    const uInt chunk = static_cast<uInt>(std::min<std::uint64_t>(bytes, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    bytes -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

void writeCheckpointFrame(std::ostream& out, const CheckpointKind& kind,
                          const std::function<void(std::ostream&)>& payload) {
  Header h{};
  std::memcpy(h.data(), kMagic, sizeof kMagic);
  putLe(h, kVersionAt, kCheckpointFormatVersion, 4);
  putLe(h, kHeaderSizeAt, kCheckpointHeaderBytes, 4);
  putText(h, kKindAt, kKindBytes, kind.name);
  putText(h, kWriterAt, kWriterBytes, std::string("CraterKit ") + kCraterKitVersion);
  const std::streampos start = out.tellp();
  // The header's sizes and checksums are filled in once the payload is written.
  out.write(reinterpret_cast<const char*>(h.data()), static_cast<std::streamsize>(h.size()));
  if (!out || start == std::streampos(-1))
    throw std::runtime_error(std::string("writing the ") + kind.description + " failed");
  CrcBuffer buffer(out.rdbuf());
  std::ostream counted(&buffer);
  payload(counted);
  counted.flush();
  if (!counted)
    throw std::runtime_error(std::string("writing the ") + kind.description + " failed");
  putLe(h, kPayloadSizeAt, buffer.bytes, 8);
  putLe(h, kPayloadCrcAt, buffer.crc, 4);
  putLe(h, kHeaderCrcAt, checkpointCrc32(h.data(), kHeaderCrcAt), 4);
  const std::streampos end = out.tellp();
  out.seekp(start);
  out.write(reinterpret_cast<const char*>(h.data()), static_cast<std::streamsize>(h.size()));
  out.seekp(end);
  if (!out)
    throw std::runtime_error(std::string("writing the ") + kind.description + " failed");
}

void writeCheckpointFile(const std::string& path, const CheckpointKind& kind,
                         const std::function<void(std::ostream&)>& payload) {
  writeFileAtomically(path, std::string("the ") + kind.description,
                      [&](std::ostream& out) { writeCheckpointFrame(out, kind, payload); });
}

std::string checkpointBytes(const CheckpointKind& kind,
                            const std::function<void(std::ostream&)>& payload) {
  CountingBuffer counter;
  std::ostream counted(&counter);
  payload(counted);
  std::string bytes(kCheckpointHeaderBytes + counter.bytes, '\0');
  SpanBuffer span(bytes.data(), bytes.size());
  std::ostream out(&span);
  writeCheckpointFrame(out, kind, payload);
  if (static_cast<std::uint64_t>(out.tellp()) != bytes.size())
    throw std::logic_error(std::string("the ") + kind.description +
                           " wrote a payload of another size the second time");
  return bytes;
}

void readCheckpointBytes(const std::string& bytes,
                         const std::function<void(std::istream&, std::uint64_t)>& read) {
  SpanBuffer span(const_cast<char*>(bytes.data()), bytes.size()); // read only: no put
  std::istream in(&span);
  read(in, bytes.size());
}

CheckpointFrame readCheckpointFrame(std::istream& in, std::uint64_t available,
                                    const CheckpointKind& kind) {
  const std::string what = kind.description;
  const std::streampos start = in.tellg();
  Header h{};
  const std::uint64_t first = std::min<std::uint64_t>(available, h.size());
  if (start == std::streampos(-1) ||
      !in.read(reinterpret_cast<char*>(h.data()), static_cast<std::streamsize>(first)))
    throw InputError("the " + what + " cannot be read");
  if (available < sizeof kMagic)
    throw InputError("the " + what + " is truncated (" + sizeText(available) + ")");
  CheckpointFrame frame;
  if (std::memcmp(h.data(), kind.legacyMagic, sizeof kind.legacyMagic) == 0) {
    // Version 1: the bare payload, read as before.
    in.clear();
    in.seekg(start);
    frame.version = 1;
    frame.payloadBytes = available;
    frame.warning = "an old " + what +
                    " (format version 1, without a checksum): read without an integrity check";
    return frame;
  }
  if (std::memcmp(h.data(), kMagic, sizeof kMagic) != 0)
    throw InputError("not a CraterKit " + what + " (unknown magic)");
  if (available < h.size())
    throw InputError("the " + what + " is truncated (" + sizeText(available) +
                     ", shorter than its header)");
  frame.version = static_cast<std::uint32_t>(getLe(h, kVersionAt, 4));
  if (frame.version != kCheckpointFormatVersion)
    throw InputError("the " + what + " has format version " + std::to_string(frame.version) +
                     ", which this CraterKit cannot read (it reads versions 1 and " +
                     std::to_string(kCheckpointFormatVersion) +
                     "): written by a newer CraterKit, or corrupt");
  if (checkpointCrc32(h.data(), kHeaderCrcAt) != getLe(h, kHeaderCrcAt, 4))
    throw InputError("the checkpoint is corrupt (checksum mismatch in its header)");
  const std::string found = getText(h, kKindAt, kKindBytes);
  if (found != kind.name)
    throw InputError("a checkpoint of kind \"" + found + "\", not of kind \"" + kind.name + "\" (" +
                     what + ")");
  if (getLe(h, kHeaderSizeAt, 4) != h.size())
    throw InputError("the checkpoint is corrupt (header size " +
                     std::to_string(getLe(h, kHeaderSizeAt, 4)) + ")");
  frame.writer = getText(h, kWriterAt, kWriterBytes);
  frame.payloadBytes = getLe(h, kPayloadSizeAt, 8);
  const std::uint64_t after = available - h.size();
  if (frame.payloadBytes > after)
    throw InputError("the " + what + " is truncated (" + sizeText(after) + " after its header, " +
                     sizeText(frame.payloadBytes) + " written)");
  if (frame.payloadBytes < after)
    throw InputError("the " + what + " has " + sizeText(after - frame.payloadBytes) +
                     " after its end");
  // The payload's checksum, before any of it is parsed.
  std::vector<char> chunk(std::min<std::uint64_t>(frame.payloadBytes, 1u << 20));
  std::uint32_t crc = 0;
  for (std::uint64_t left = frame.payloadBytes; left > 0;) {
    const std::uint64_t n = std::min<std::uint64_t>(left, chunk.size());
    if (!in.read(chunk.data(), static_cast<std::streamsize>(n)))
      throw InputError("the " + what + " cannot be read (truncated while reading)");
    crc = checkpointCrc32(chunk.data(), n, crc);
    left -= n;
  }
  if (crc != getLe(h, kPayloadCrcAt, 4))
    throw InputError("the checkpoint is corrupt (checksum mismatch)");
  in.clear();
  in.seekg(start + static_cast<std::streamoff>(h.size()));
  if (!in)
    throw InputError("the " + what + " cannot be read (seek failed)");
  return frame;
}

void readCheckpointFile(const std::string& path, const CheckpointKind& kind,
                        const std::function<void(std::istream&, const CheckpointFrame&)>& read) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
    throw InputError(path + ": cannot open the " + kind.description);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  if (size < 0 || !in)
    throw InputError(path + ": cannot read the " + kind.description);
  try {
    CheckpointFrame frame = readCheckpointFrame(in, static_cast<std::uint64_t>(size), kind);
    if (!frame.warning.empty())
      frame.warning = path + ": " + frame.warning;
    read(in, frame);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

} // namespace craterkit
