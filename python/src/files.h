/*
 * pcl_ncut_seg Python module: read_file(), the tools' reader of point files and meshes
 * (kit/files/point_file.h), so that the package and its batch front end read every file as the
 * pcl_ncut_seg tool reads it.
 */
#pragma once

#include <pybind11/pybind11.h>

namespace pcl_ncut_seg_python {

/** \brief Adds read_file() and input_extensions to the module. */
void defineFiles(pybind11::module_& m);

} // namespace pcl_ncut_seg_python
