/*
 * pcl_ncut_seg tests: read a PNG (with VTK's vtkPNGReader) into 8-bit RGB pixels, so that the
 * viewer's screenshots can be checked without VTK headers in the test.
 */
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief An RGB image, rows from the top, 3 bytes per pixel. */
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

/** \brief Read a PNG file; false if it cannot be read. Grey and RGBA images become RGB. */
bool readPng(const std::string& path, RgbImage& image);

} // namespace pcl_ncut_seg
