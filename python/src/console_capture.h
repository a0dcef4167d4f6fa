/*
 * pcl_ncut_seg Python module: the library reports bad input and warnings as PCL_ERROR and
 * PCL_WARN lines on stderr. ConsoleCapture takes what is written to file descriptor 2 while it
 * lives, so that the module can raise the library's reason as a ValueError and turn its
 * warnings into Python warnings.
 */
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace pcl_ncut_seg_python {

/** \brief Redirects file descriptor 2 into a temporary file from construction to finish()
 * (or destruction). Nothing is lost if the capture cannot start: stderr is then left alone. */
class ConsoleCapture {
public:
  ConsoleCapture();
  ~ConsoleCapture();
  ConsoleCapture(const ConsoleCapture&) = delete;
  ConsoleCapture& operator=(const ConsoleCapture&) = delete;

  /** \brief Restore stderr and return what was written, terminal colour codes removed. */
  std::string finish();

private:
  std::FILE* file_ = nullptr;
  int saved_fd_ = -1;
};

/** \brief Run work with stderr captured; what it wrote. One capture at a time in the process
 * (the redirection is process-wide): a second caller waits. Call it without the GIL. */
std::string runCapturingConsole(const std::function<void()>& work);

/** \brief One line PCL printed: the message without the "[pcl::Class::method] " prefix. */
struct ConsoleLine {
  bool from_pcl = false; ///< it had the "[pcl::...]" prefix
  std::string text;      ///< the message (from_pcl) or the whole line
};

/** \brief The text split into lines, PCL's prefixes recognised. */
std::vector<ConsoleLine> splitConsoleLines(const std::string& text);

} // namespace pcl_ncut_seg_python
