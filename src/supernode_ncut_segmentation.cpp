// Explicit instantiations for PCL's point types with x, y, z. Other point types: define
// PCL_NO_PRECOMPILE before including supernode_ncut_segmentation.h.
#include <pcl_ncut_seg/impl/supernode_ncut_segmentation.hpp>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/impl/instantiate.hpp>
#include <pcl/point_types.h>

PCL_INSTANTIATE(SupernodeNCutSegmentation, PCL_XYZ_POINT_TYPES)
