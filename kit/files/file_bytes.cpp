#include "files/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace files {

namespace {

constexpr std::size_t kMapBytes = 1 << 24; // from 16 MiB on, copy from a mapping of the file

} // namespace

/** Copy [offset, offset + n) from a read-only mapping: a page cache's pages are copied once
 * (pread copies them as well, but through the kernel, which is slower for large reads). */
bool FileBytes::mapCopy(std::uint64_t offset, std::size_t n, char* dst) const {
  const std::uint64_t page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t start = offset / page * page;
  const std::size_t length = static_cast<std::size_t>(offset - start) + n;
  void* map = ::mmap(nullptr, length, PROT_READ, MAP_PRIVATE, fd_, static_cast<off_t>(start));
  if (map == MAP_FAILED)
    return false;
  std::memcpy(dst, static_cast<const char*>(map) + (offset - start), n);
  ::munmap(map, length);
  return true;
}

FileBytes::~FileBytes() {
  if (fd_ >= 0)
    ::close(fd_);
}

bool FileBytes::open(const std::string& path, std::string& error) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    error = std::strerror(errno);
    return false;
  }
  struct stat st;
  if (::fstat(fd_, &st) != 0) {
    error = std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "not a regular file";
    return false;
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
  return true;
}

bool FileBytes::read(std::uint64_t offset, std::size_t n, void* out, std::string& error) const {
  if (offset > size_ || n > size_ - offset) {
    error = "the file ends after " + std::to_string(size_) + " bytes, " +
            std::to_string(offset + n) + " needed";
    return false;
  }
  auto* dst = static_cast<char*>(out);
  if (n >= kMapBytes && mapCopy(offset, n, dst))
    return true;
  while (n > 0) {
    const ssize_t got = ::pread(fd_, dst, n, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR)
      continue;
    if (got <= 0) {
      error = got < 0 ? std::strerror(errno) : "the file was cut short while it was read";
      return false;
    }
    dst += got;
    offset += static_cast<std::uint64_t>(got);
    n -= static_cast<std::size_t>(got);
  }
  return true;
}

bool FileBytes::readRest(std::uint64_t offset, std::string& out, std::string& error,
                         std::uint64_t max_bytes) const {
  const std::uint64_t n = offset >= size_ ? 0 : std::min(size_ - offset, max_bytes);
  out.resize(static_cast<std::size_t>(n));
  return read(offset, out.size(), out.data(), error);
}

bool nextLine(const std::string& text, std::size_t pos, TextLine& line) {
  if (pos >= text.size())
    return false;
  const std::size_t newline = text.find('\n', pos);
  line.begin = pos;
  line.end = newline == std::string::npos ? text.size() : newline;
  line.next = newline == std::string::npos ? text.size() : newline + 1;
  if (line.end > line.begin && text[line.end - 1] == '\r')
    --line.end;
  return true;
}

std::string quoted(const char* begin, const char* end) {
  std::string s(begin, std::min<std::size_t>(static_cast<std::size_t>(end - begin), 40));
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126)
      c = '?';
  return "'" + s + (end - begin > 40 ? "...'" : "'");
}

} // namespace files
} // namespace pcl_ncut_seg
