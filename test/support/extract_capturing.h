/*
 * extract() and what it printed on stderr (PCL_ERROR and PCL_WARN go there), for tests of
 * bad input and bad parameters.
 */
#pragma once

#include <pcl/PointIndices.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

struct Extracted {
  std::vector<pcl::PointIndices> segments;
  std::string err;
};

/** seg.extract() into a vector that held stale segments (extract() must clear them). */
template <typename Seg> Extracted extractCapturing(Seg& seg) {
  Extracted r;
  r.segments.resize(2);
  ::testing::internal::CaptureStderr();
  seg.extract(r.segments);
  r.err = ::testing::internal::GetCapturedStderr();
  return r;
}

} // namespace test
} // namespace pcl_ncut_seg
