/*
 * pcl_ncut_seg files: the bytes of an input file, read with bounds checked. Every reader in
 * files/ reads through a FileBytes, so that no header can make it read past the file's end or
 * allocate more than the file can hold.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcl_ncut_seg {
namespace files {

/** \brief A regular file opened for reading: its size, and reads at an offset that fail
 * instead of running past the end. */
class FileBytes {
public:
  FileBytes() = default;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();

  /** \brief Open path; false with the reason ("No such file or directory", "not a regular
   * file") in error. */
  bool open(const std::string& path, std::string& error);
  std::uint64_t size() const { return size_; }

  /** \brief Read n bytes at offset into out; false (and a reason) when the file is shorter or
   * the read fails. */
  bool read(std::uint64_t offset, std::size_t n, void* out, std::string& error) const;
  /** \brief The bytes from offset to the end, at most max_bytes of them (all: no bound). */
  bool readRest(std::uint64_t offset, std::string& out, std::string& error,
                std::uint64_t max_bytes = UINT64_MAX) const;

private:
  bool mapCopy(std::uint64_t offset, std::size_t n, char* dst) const;

  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/** \brief One line of a text header or body: [begin, end) without its line end ("\n" or
 * "\r\n"); next is where the following line starts. */
struct TextLine {
  std::size_t begin = 0, end = 0, next = 0;
};

/** \brief The line of text starting at pos; false at the end of text. A line without a
 * final "\n" ends at the text's end. */
bool nextLine(const std::string& text, std::size_t pos, TextLine& line);

/** \brief Whether a character separates values on a text line (space, tab, or '\r'). */
inline bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/** \brief Shown in a message: at most 40 characters of the token, non-printable bytes as '?'. */
std::string quoted(const char* begin, const char* end);

} // namespace files
} // namespace pcl_ncut_seg
