/*
 * pcl_ncut_seg ROS: the nodelet pcl_ncut_seg/SupernodeNCutSegmentation, in the manner of
 * pcl_ros's segmentation nodelets.
 *
 * Topics (private): ~input (sensor_msgs/PointCloud2) in; ~indices (pcl_msgs/PointIndices) in
 * when ~use_indices, synchronized exactly or, with ~approximate_sync, approximately; ~output
 * out: the input labelled (x y z rgb label, the input's header and layout), or with
 * ~publish_indices one pcl_msgs/PointIndices per segment; ~stats (std_msgs/String, latched):
 * what the last segmentation did, as YAML. The input is subscribed only while ~output has a
 * subscriber (~lazy, default true).
 *
 * Parameters (private): every row of parameter_table.h by its name (~k, ~segments,
 * ~boundary_band ...), read at start-up; the cut stages' rows also through
 * dynamic_reconfigure, where a change re-cuts the last cloud on its kept analysis and
 * publishes it again. ~max_queue_size (3), ~use_indices, ~approximate_sync, ~publish_indices
 * (false). ~sensor_frame (""): the sensor's frame, whose origin in the cloud's frame at the
 * cloud's stamp (from TF, waiting at most ~sensor_frame_timeout, 0.1 s) is the cloud's sensor
 * origin; empty: the cloud's own frame is the sensor's.
 */
#pragma once

#include <pcl_ncut_seg_ros/cloud_segmenter.h>
#include <pcl_ncut_seg_ros/ros_parameters.h>

#include <dynamic_reconfigure/server.h>
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <nodelet_topic_tools/nodelet_lazy.h>
#include <pcl_msgs/PointIndices.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <boost/thread/recursive_mutex.hpp>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace pcl_ncut_seg_ros {

class SegmentationNodelet : public nodelet_topic_tools::NodeletLazy {
public:
  SegmentationNodelet();
  ~SegmentationNodelet() override;

protected:
  void onInit() override;
  void subscribe() override;
  void unsubscribe() override;

private:
  using Cloud = sensor_msgs::PointCloud2;
  using Indices = pcl_msgs::PointIndices;
  using ExactSync =
      message_filters::Synchronizer<message_filters::sync_policies::ExactTime<Cloud, Indices>>;
  using ApproximateSync = message_filters::Synchronizer<
      message_filters::sync_policies::ApproximateTime<Cloud, Indices>>;

  void cloudCallback(const Cloud::ConstPtr& cloud);
  void cloudIndicesCallback(const Cloud::ConstPtr& cloud, const Indices::ConstPtr& indices);
  /** \brief Read ~sensor_frame and ~sensor_frame_timeout; listen to TF when one is set. */
  void initSensorFrame();
  void process(const Cloud& cloud, const std::vector<int>* indices);
  /** \brief The sensor origin for the cloud: ~sensor_frame's origin from TF, or what to use
   * instead (the cloud's frame when ~sensor_frame is empty, else the points). */
  SensorOrigin sensorOrigin(const Cloud& cloud);
  void reconfigure(Config& config, std::uint32_t level);
  /** \brief Publish the segmenter's result on ~output and ~stats (mutex_ held). */
  void publish();
  /** \brief The library's warnings of the last segmentation, as NODELET_WARN (mutex_ held). */
  void logWarnings();

  int max_queue_size_ = 3;
  bool use_indices_ = false;
  bool approximate_sync_ = false;
  bool publish_indices_ = false;
  std::string sensor_frame_;
  double sensor_frame_timeout_ = 0.1;

  ros::Subscriber sub_input_;
  message_filters::Subscriber<Cloud> sub_input_filter_;
  message_filters::Subscriber<Indices> sub_indices_filter_;
  std::shared_ptr<ExactSync> exact_sync_;
  std::shared_ptr<ApproximateSync> approximate_sync_filter_;
  ros::Publisher pub_output_, pub_stats_;
  // With ~sensor_frame: the listener fills the buffer on a thread of its own, so that a
  // lookup's wait inside a cloud callback sees transforms arrive.
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;

  std::mutex mutex_; ///< the segmenter's: clouds and reconfigurations may come on two threads
  CloudSegmenter segmenter_;

  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<Config>> reconfigure_server_;
  bool reconfigure_ready_ = false; ///< false during the server's first call (start-up wins)
};

} // namespace pcl_ncut_seg_ros
