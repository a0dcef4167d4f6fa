/*
 * pcl_ncut_seg ROS: every row of parameter_table.h read from the node's private parameters at
 * start-up, and the cut-stage rows to and from dynamic_reconfigure's Config.
 */
#pragma once

#include <pcl_ncut_seg/SupernodeNCutSegmentationConfig.h>
#include <pcl_ncut_seg/parameters.h>
#include <pcl_ncut_seg_ros/parameter_values.h>

#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace pcl_ncut_seg_ros {

/** \brief The Config class dynamic_reconfigure generates from the table's cut-stage rows. */
using Config = pcl_ncut_seg::SupernodeNCutSegmentationConfig;

/** \brief An XmlRpc value (int, double, bool or string) as a Value; false for another type. */
bool fromXmlRpc(const XmlRpc::XmlRpcValue& xml, Value& value);

/** \brief Set every row of the table found among private_nh's parameters. A bad value is
 * reported by ROS_ERROR naming the parameter and its range, and the row keeps its value in
 * params. A private parameter that is no row and not in other_names (the node's own, such as
 * max_queue_size) gets a ROS_WARN. Returns the number of rejected values. */
int readParameters(const ros::NodeHandle& private_nh, pcl_ncut_seg::Parameters& params,
                   const std::vector<std::string>& other_names);

/** \brief The Config holding params' values of the reconfigurable rows (off: 0). */
Config toConfig(const pcl_ncut_seg::Parameters& params);

/** \brief Take into params each value of config that differs from it, in the table's order;
 * a value the table rejects leaves its row unchanged and adds a message to the result. */
std::vector<std::string> applyConfig(const Config& config, pcl_ncut_seg::Parameters& params);

} // namespace pcl_ncut_seg_ros
