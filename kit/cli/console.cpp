#include "cli/console.h"

#include "cli/build_info.h"

#include <pcl/console/print.h>

#include <cstdio>

namespace pcl_ncut_seg {
namespace tool {

void fail(const std::string& message) {
  pcl::console::print_error("Error: %s\n", message.c_str());
}

void printVersion() {
  std::printf("pcl_ncut_seg %s (build %s)\n", projectVersion(), buildDescription());
}

void warn(const std::string& message) {
  pcl::console::print_warn("Warning: %s\n", message.c_str());
}

SilencePcl::SilencePcl() : level_(pcl::console::getVerbosityLevel()) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
}

SilencePcl::~SilencePcl() {
  pcl::console::setVerbosityLevel(static_cast<pcl::console::VERBOSITY_LEVEL>(level_));
}

} // namespace tool
} // namespace pcl_ncut_seg
