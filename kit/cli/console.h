/*
 * pcl_ncut_seg tools: one-line messages on stderr, and silencing PCL's own console output.
 */
#pragma once

#include <string>

namespace pcl_ncut_seg {
namespace tool {

/** \brief One error line on stderr, in PCL's style ("Error: ..."). */
void fail(const std::string& message);
/** \brief One warning line on stderr ("Warning: ..."). */
void warn(const std::string& message);

/** \brief "pcl_ncut_seg VERSION (build BUILD)" on stdout, for -version. */
void printVersion();

/** \brief Silences PCL's own console messages while in scope. */
class SilencePcl {
public:
  SilencePcl();
  ~SilencePcl();
  SilencePcl(const SilencePcl&) = delete;
  SilencePcl& operator=(const SilencePcl&) = delete;

private:
  int level_;
};

} // namespace tool
} // namespace pcl_ncut_seg
