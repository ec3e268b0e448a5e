// A file's bytes for the parsers of io/: a plain file memory-mapped (mmap(2), read-only), a
// gzip file (RFC 1952, recognised by its magic 1f 8b) inflated into memory with zlib.
#pragma once

#include "io/ParticleFrame.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace craterkit {

// A file's bytes without a copy: a plain file is memory-mapped read-only (the page cache is
// read in place, populated up front); a gzip file (by its magic) is decompressed into memory.
// Throws ParseError naming the file. Mapped bytes are only valid while the file is not
// truncated by another program, so keep the object no longer than a parse (the dump reader
// keeps a copy of a dump of several snapshots, see readFileBytes).
class FileBytes {
public:
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::string_view view() const {
    return map_ ? std::string_view(map_, size_) : std::string_view(owned_);
  }

private:
  const char* map_ = nullptr;
  std::size_t size_ = 0;
  std::string owned_;
};

// The whole file as a string, gunzipped if it starts with the gzip magic; throws ParseError
// naming it.
std::string readFileBytes(const std::string& path);
// Decompresses a gzip stream held in memory (output capped at 1032 times the input).
std::string gunzip(std::string_view data, const std::string& name);

} // namespace craterkit
