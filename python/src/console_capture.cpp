#include "console_capture.h"

#include <unistd.h>

#include <mutex>

namespace pcl_ncut_seg_python {

ConsoleCapture::ConsoleCapture() {
  std::fflush(stderr);
  file_ = std::tmpfile();
  if (!file_)
    return;
  saved_fd_ = ::dup(2);
  if (saved_fd_ < 0 || ::dup2(::fileno(file_), 2) < 0) {
    if (saved_fd_ >= 0)
      ::close(saved_fd_);
    saved_fd_ = -1;
    std::fclose(file_);
    file_ = nullptr;
  }
}

ConsoleCapture::~ConsoleCapture() {
  finish();
}

std::string ConsoleCapture::finish() {
  if (!file_)
    return std::string();
  std::fflush(stderr);
  ::dup2(saved_fd_, 2);
  ::close(saved_fd_);
  saved_fd_ = -1;
  std::string raw;
  std::rewind(file_);
  char buffer[4096];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file_)) > 0;)
    raw.append(buffer, got);
  std::fclose(file_);
  file_ = nullptr;
  // Terminal colour codes (ESC [ ... letter), which PCL adds on a terminal.
  std::string text;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] == '\x1b' && i + 1 < raw.size() && raw[i + 1] == '[') {
      i += 2;
      while (i < raw.size() &&
             !((raw[i] >= 'A' && raw[i] <= 'Z') || (raw[i] >= 'a' && raw[i] <= 'z')))
        ++i;
      continue;
    }
    text += raw[i];
  }
  return text;
}

std::string runCapturingConsole(const std::function<void()>& work) {
  static std::mutex one_at_a_time;
  std::lock_guard<std::mutex> lock(one_at_a_time);
  ConsoleCapture capture;
  work();
  return capture.finish();
}

std::vector<ConsoleLine> splitConsoleLines(const std::string& text) {
  std::vector<ConsoleLine> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos)
      end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    if (line.empty())
      continue;
    ConsoleLine l;
    const std::size_t close = line.find("] ");
    if (line.compare(0, 6, "[pcl::") == 0 && close != std::string::npos) {
      l.from_pcl = true;
      l.text = line.substr(close + 2);
    } else {
      l.text = line;
    }
    lines.push_back(l);
  }
  return lines;
}

} // namespace pcl_ncut_seg_python
