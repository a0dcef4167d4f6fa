/*
 * pcl_ncut_seg ROS: pcl_ncut_seg_node, the nodelet pcl_ncut_seg/SupernodeNCutSegmentation run
 * as a node of its own (no nodelet manager): the same topics and parameters, in the node's
 * private namespace.
 *
 *   rosrun pcl_ncut_seg pcl_ncut_seg_node ~input:=/camera/depth/points _segments:=4
 */
#include <pcl_ncut_seg_ros/segmentation_nodelet.h>

#include <ros/ros.h>

#include <string>

int main(int argc, char** argv) {
  ros::init(argc, argv, "pcl_ncut_seg_node");
  pcl_ncut_seg_ros::SegmentationNodelet nodelet;
  // Callbacks on ros::spin()'s thread: clouds and reconfigurations one at a time.
  nodelet.init(ros::this_node::getName(), ros::names::getRemappings(),
               nodelet::V_string(argv + 1, argv + argc));
  ros::spin();
  return 0;
}
