#include "io/FileBytes.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>

#include <algorithm>
#include <cstring>
#include <limits>

namespace craterkit {

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
