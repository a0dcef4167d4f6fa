#include <pcl_ncut_seg_ros/segmentation_nodelet.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <pluginlib/class_list_macros.hpp>
#include <std_msgs/String.h>

#include <boost/bind/bind.hpp>
#include <boost/make_shared.hpp>

#include <string>

namespace pcl_ncut_seg_ros {

namespace {

/// Seconds between two warnings that ~sensor_frame has no transform.
constexpr double kTfWarningPeriod = 5.0;

/** \brief Do the two hold the same value in every row? */
bool sameParameters(const pcl_ncut_seg::Parameters& a, const pcl_ncut_seg::Parameters& b) {
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (row.get(a) != row.get(b))
      return false;
  return true;
}

/** \brief The rows that differ from the defaults, "k=12 segments=4", or "defaults". */
std::string changedRows(const pcl_ncut_seg::Parameters& params) {
  const pcl_ncut_seg::Parameters defaults;
  std::string out;
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (row.get(params) != row.get(defaults))
      out += (out.empty() ? "" : " ") + row.name + "=" + row.get(params);
  return out.empty() ? "defaults" : out;
}

} // namespace

SegmentationNodelet::SegmentationNodelet() = default;
SegmentationNodelet::~SegmentationNodelet() = default;

void SegmentationNodelet::onInit() {
  NodeletLazy::onInit();
  pnh_->getParam("max_queue_size", max_queue_size_);
  pnh_->getParam("use_indices", use_indices_);
  pnh_->getParam("approximate_sync", approximate_sync_);
  pnh_->getParam("publish_indices", publish_indices_);
  if (max_queue_size_ < 1) {
    NODELET_ERROR("~max_queue_size must be an integer >= 1, got %d; using 3", max_queue_size_);
    max_queue_size_ = 3;
  }
  initSensorFrame();

  // Every parameter of the table from the private parameters, before dynamic_reconfigure's
  // server writes its own values over them.
  pcl_ncut_seg::Parameters params;
  readParameters(*pnh_, params,
                 {"max_queue_size", "use_indices", "approximate_sync", "publish_indices",
                  "sensor_frame", "sensor_frame_timeout", "lazy", "verbose_connection",
                  "duration_to_warn_no_connection", "use_multithread_callback"});
  std::string why;
  if (!segmenter_.setParameters(params, &why))
    NODELET_ERROR("parameters not taken: %s; using the defaults", why.c_str());

  if (publish_indices_)
    pub_output_ = advertise<Indices>(*pnh_, "output", max_queue_size_);
  else
    pub_output_ = advertise<Cloud>(*pnh_, "output", max_queue_size_);
  pub_stats_ = pnh_->advertise<std_msgs::String>("stats", 1, true);

  // The server publishes the parameter server's values as it starts: put the values taken
  // there first (a rejected one is the kept default), or a client that connects before
  // updateConfig() below sees the rejected value clamped to its range.
  toConfig(segmenter_.parameters()).__toServer__(*pnh_);
  reconfigure_server_ =
      std::make_unique<dynamic_reconfigure::Server<Config>>(reconfigure_mutex_, *pnh_);
  reconfigure_server_->setCallback(boost::bind(&SegmentationNodelet::reconfigure, this,
                                               boost::placeholders::_1, boost::placeholders::_2));
  reconfigure_ready_ = true;
  reconfigure_server_->updateConfig(toConfig(segmenter_.parameters()));

  NODELET_INFO("segmenting %s into %s (%s%s), seen from %s; parameters: %s",
               pnh_->resolveName("input").c_str(), pnh_->resolveName("output").c_str(),
               publish_indices_ ? "pcl_msgs/PointIndices per segment" : "x y z rgb label",
               use_indices_ ? (approximate_sync_ ? ", ~indices approximately synchronized"
                                                 : ", ~indices exactly synchronized")
                            : "",
               sensor_frame_.empty() ? "each cloud's frame"
                                     : ("the origin of " + sensor_frame_ + " (TF)").c_str(),
               changedRows(segmenter_.parameters()).c_str());
  onInitPostProcess();
}

void SegmentationNodelet::initSensorFrame() {
  pnh_->getParam("sensor_frame", sensor_frame_);
  pnh_->getParam("sensor_frame_timeout", sensor_frame_timeout_);
  if (!(sensor_frame_timeout_ >= 0.0 && sensor_frame_timeout_ <= 10.0)) { // NaN too
    NODELET_ERROR("~sensor_frame_timeout must be a number of seconds in [0, 10], got %g; using 0.1",
                  sensor_frame_timeout_);
    sensor_frame_timeout_ = 0.1;
  }
  if (!sensor_frame_.empty() && sensor_frame_[0] == '/') { // tf2 takes no leading slash
    NODELET_WARN("~sensor_frame '%s': using '%s'", sensor_frame_.c_str(),
                 sensor_frame_.substr(1).c_str());
    sensor_frame_.erase(0, 1);
  }
  if (sensor_frame_.empty())
    return;
  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, *nh_, true);
}

void SegmentationNodelet::subscribe() {
  if (!use_indices_) {
    sub_input_ =
        pnh_->subscribe("input", max_queue_size_, &SegmentationNodelet::cloudCallback, this);
    return;
  }
  sub_input_filter_.subscribe(*pnh_, "input", max_queue_size_);
  sub_indices_filter_.subscribe(*pnh_, "indices", max_queue_size_);
  const auto callback = boost::bind(&SegmentationNodelet::cloudIndicesCallback, this,
                                    boost::placeholders::_1, boost::placeholders::_2);
  if (approximate_sync_) {
    approximate_sync_filter_ = std::make_shared<ApproximateSync>(
        message_filters::sync_policies::ApproximateTime<Cloud, Indices>(max_queue_size_),
        sub_input_filter_, sub_indices_filter_);
    approximate_sync_filter_->registerCallback(callback);
  } else {
    exact_sync_ = std::make_shared<ExactSync>(
        message_filters::sync_policies::ExactTime<Cloud, Indices>(max_queue_size_),
        sub_input_filter_, sub_indices_filter_);
    exact_sync_->registerCallback(callback);
  }
}

void SegmentationNodelet::unsubscribe() {
  if (use_indices_) {
    sub_input_filter_.unsubscribe();
    sub_indices_filter_.unsubscribe();
  } else {
    sub_input_.shutdown();
  }
}

void SegmentationNodelet::cloudCallback(const Cloud::ConstPtr& cloud) {
  process(*cloud, nullptr);
}

void SegmentationNodelet::cloudIndicesCallback(const Cloud::ConstPtr& cloud,
                                               const Indices::ConstPtr& indices) {
  if (indices->header.frame_id != cloud->header.frame_id)
    NODELET_WARN("~indices are in frame %s, ~input in %s", indices->header.frame_id.c_str(),
                 cloud->header.frame_id.c_str());
  const std::vector<int> list(indices->indices.begin(), indices->indices.end());
  process(*cloud, &list);
}

SensorOrigin SegmentationNodelet::sensorOrigin(const Cloud& cloud) {
  SensorOrigin origin;
  if (sensor_frame_.empty())
    return origin;
  const std::string& frame = cloud.header.frame_id;
  std::string why;
  if (frame.empty() || frame[0] == '/') { // tf2 would complain at every poll of its wait
    why = frame.empty() ? "the cloud has no frame_id" : "tf2 takes no frame_id with a leading /";
  } else {
    try {
      const geometry_msgs::Vector3 t =
          tf_buffer_
              ->lookupTransform(frame, sensor_frame_, cloud.header.stamp,
                                ros::Duration(sensor_frame_timeout_))
              .transform.translation;
      origin.source = SensorOrigin::Source::Tf;
      origin.xyz[0] = t.x;
      origin.xyz[1] = t.y;
      origin.xyz[2] = t.z;
      return origin;
    } catch (const tf2::TransformException& e) {
      why = e.what();
    }
  }
  NODELET_WARN_THROTTLE(kTfWarningPeriod,
                        "no transform from ~sensor_frame '%s' to the cloud's frame '%s' at %.6f "
                        "(%s): the sensor's position is read off the points",
                        sensor_frame_.c_str(), frame.c_str(), cloud.header.stamp.toSec(),
                        why.c_str());
  origin.source = SensorOrigin::Source::Points;
  return origin;
}

void SegmentationNodelet::process(const Cloud& cloud, const std::vector<int>* indices) {
  // Only a cloud that can be segmented is worth a wait for its transform, outside the lock.
  std::string why = checkCloud(cloud);
  const SensorOrigin origin = why.empty() ? sensorOrigin(cloud) : SensorOrigin();
  std::lock_guard<std::mutex> lock(mutex_);
  if (!why.empty() || !segmenter_.segment(cloud, indices, &why, origin)) {
    NODELET_ERROR("cloud of frame '%s' at %.6f not segmented: %s", cloud.header.frame_id.c_str(),
                  cloud.header.stamp.toSec(), why.c_str());
    return;
  }
  logWarnings();
  const SegmentStats& s = segmenter_.stats();
  NODELET_DEBUG("%zu points: %zu segments (analysis %.3f s, cut %.3f s)", s.points, s.segments,
                s.analysis_seconds, s.cut_seconds);
  publish();
}

void SegmentationNodelet::reconfigure(Config& config, std::uint32_t /*level*/) {
  if (!reconfigure_ready_)
    return; // the server's first call: the parameters read at start-up stand
  std::lock_guard<std::mutex> lock(mutex_);
  pcl_ncut_seg::Parameters params = segmenter_.parameters();
  for (const std::string& why : applyConfig(config, params))
    NODELET_ERROR("dynamic_reconfigure: %s; keeping the previous value", why.c_str());
  std::string why;
  const bool changed = !sameParameters(params, segmenter_.parameters());
  if (changed && !segmenter_.setParameters(params, &why))
    NODELET_ERROR("dynamic_reconfigure: %s; keeping the previous parameters", why.c_str());
  config = toConfig(segmenter_.parameters()); // what was taken, as the clients should see it
  if (!changed || !segmenter_.hasCloud())
    return;
  if (!segmenter_.recut(&why)) {
    NODELET_ERROR("dynamic_reconfigure: the last cloud was not re-cut: %s", why.c_str());
    return;
  }
  logWarnings();
  const SegmentStats& s = segmenter_.stats();
  if (s.analysed)
    NODELET_INFO("re-segmented the last cloud: %zu segments (analysis %.3f s, needed by the new "
                 "parameters; cut %.3f s)",
                 s.segments, s.analysis_seconds, s.cut_seconds);
  else
    NODELET_INFO("re-cut the last cloud on its kept analysis: %zu segments in %.3f s (the "
                 "analysis, %.3f s, was not repeated)",
                 s.segments, s.cut_seconds, s.analysis_seconds);
  publish();
}

void SegmentationNodelet::logWarnings() {
  for (const pcl_ncut_seg::Warning& w : segmenter_.status().warnings)
    NODELET_WARN("%s", w.message.c_str());
}

void SegmentationNodelet::publish() {
  if (publish_indices_) {
    for (const Indices& segment : segmenter_.segmentIndices())
      pub_output_.publish(boost::make_shared<Indices>(segment));
  } else {
    // Shared: a nodelet in the same manager gets it without a copy.
    const auto out = boost::make_shared<Cloud>();
    segmenter_.labelledCloud(*out);
    pub_output_.publish(out);
  }
  std_msgs::String stats;
  stats.data = segmenter_.stats().yaml();
  pub_stats_.publish(stats);
}

} // namespace pcl_ncut_seg_ros

PLUGINLIB_EXPORT_CLASS(pcl_ncut_seg_ros::SegmentationNodelet, nodelet::Nodelet)
