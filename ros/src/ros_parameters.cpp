#include <pcl_ncut_seg_ros/ros_parameters.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <dynamic_reconfigure/config_tools.h>
#include <ros/console.h>

#include <boost/any.hpp>

#include <algorithm>

namespace pcl_ncut_seg_ros {

using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::Parameters;

bool fromXmlRpc(const XmlRpc::XmlRpcValue& xml, Value& value) {
  XmlRpc::XmlRpcValue v = xml; // its conversions are not const
  switch (v.getType()) {
  case XmlRpc::XmlRpcValue::TypeInt:
    value = Value::ofInteger(static_cast<int>(v));
    return true;
  case XmlRpc::XmlRpcValue::TypeDouble:
    value = Value::ofReal(static_cast<double>(v));
    return true;
  case XmlRpc::XmlRpcValue::TypeBoolean:
    value = Value::ofBoolean(static_cast<bool>(v));
    return true;
  case XmlRpc::XmlRpcValue::TypeString:
    value = Value::ofText(static_cast<std::string>(v));
    return true;
  default:
    return false;
  }
}

namespace {

/** \brief The names of private_nh's own parameters (one level below its namespace). */
std::vector<std::string> privateNames(const ros::NodeHandle& private_nh) {
  std::vector<std::string> all, names;
  if (!private_nh.getParamNames(all))
    return names;
  const std::string prefix = private_nh.getNamespace() + "/";
  for (const std::string& key : all)
    if (key.compare(0, prefix.size(), prefix) == 0) {
      const std::string name = key.substr(prefix.size());
      const std::string first = name.substr(0, name.find('/'));
      if (std::find(names.begin(), names.end(), first) == names.end())
        names.push_back(first);
    }
  return names;
}

} // namespace

int readParameters(const ros::NodeHandle& private_nh, Parameters& params,
                   const std::vector<std::string>& other_names) {
  int rejected = 0;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable()) {
    XmlRpc::XmlRpcValue xml;
    if (!private_nh.getParam(row.name, xml))
      continue;
    Value value;
    std::string why;
    if (!fromXmlRpc(xml, value))
      why = row.name + " must be " + row.range + ", got a parameter of another type";
    if (why.empty() && setFromValue(params, row, value, &why))
      continue;
    ROS_ERROR("~%s: %s; keeping %s", row.name.c_str(), why.c_str(), row.get(params).c_str());
    ++rejected;
  }
  for (const std::string& name : privateNames(private_nh)) {
    if (std::find(other_names.begin(), other_names.end(), name) != other_names.end())
      continue;
    if (!pcl_ncut_seg::findParameter(name))
      ROS_WARN("~%s is no parameter of the segmentation; it is ignored", name.c_str());
  }
  return rejected;
}

Config toConfig(const Parameters& params) {
  dynamic_reconfigure::Config msg;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable()) {
    if (!isReconfigurable(row))
      continue;
    const Value v = typedValue(row, params);
    switch (v.type) {
    case Value::Type::Integer:
      dynamic_reconfigure::ConfigTools::appendParameter(msg, row.name, static_cast<int>(v.integer));
      break;
    case Value::Type::Real:
      dynamic_reconfigure::ConfigTools::appendParameter(msg, row.name, v.real);
      break;
    case Value::Type::Boolean:
      dynamic_reconfigure::ConfigTools::appendParameter(msg, row.name, v.boolean);
      break;
    case Value::Type::Text:
      dynamic_reconfigure::ConfigTools::appendParameter(msg, row.name, v.text);
      break;
    }
  }
  Config config = Config::__getDefault__();
  config.__fromMessage__(msg);
  return config;
}

std::vector<std::string> applyConfig(const Config& config, Parameters& params) {
  std::vector<std::string> rejected;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable()) {
    if (!isReconfigurable(row))
      continue;
    for (const Config::AbstractParamDescriptionConstPtr& d : Config::__getParamDescriptions__()) {
      if (d->name != row.name)
        continue;
      boost::any any;
      d->getValue(config, any);
      Value value;
      if (d->type == "int")
        value = Value::ofInteger(boost::any_cast<int>(any));
      else if (d->type == "double")
        value = Value::ofReal(boost::any_cast<double>(any));
      else if (d->type == "bool")
        value = Value::ofBoolean(boost::any_cast<bool>(any));
      else
        value = Value::ofText(boost::any_cast<std::string>(any));
      std::string text, why;
      if (!valueText(row, value, text, &why))
        rejected.push_back(why);
      else if (text != row.get(params) && !row.set(params, text, &why))
        rejected.push_back(why);
    }
  }
  return rejected;
}

} // namespace pcl_ncut_seg_ros
