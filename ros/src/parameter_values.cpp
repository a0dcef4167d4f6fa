#include <pcl_ncut_seg_ros/parameter_values.h>

#include <cstdlib>
#include <utility>

namespace pcl_ncut_seg_ros {

using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::Stage;
using pcl_ncut_seg::ValueKind;

Value Value::ofInteger(long long v) {
  Value value;
  value.type = Type::Integer;
  value.integer = v;
  return value;
}

Value Value::ofReal(double v) {
  Value value;
  value.type = Type::Real;
  value.real = v;
  return value;
}

Value Value::ofBoolean(bool v) {
  Value value;
  value.type = Type::Boolean;
  value.boolean = v;
  return value;
}

Value Value::ofText(std::string v) {
  Value value;
  value.type = Type::Text;
  value.text = std::move(v);
  return value;
}

std::string Value::describe() const {
  switch (type) {
  case Type::Integer:
    return std::to_string(integer);
  case Type::Real:
    return pcl_ncut_seg::formatNumber(real);
  case Type::Boolean:
    return boolean ? "true" : "false";
  case Type::Text:
    break;
  }
  return "'" + text + "'";
}

bool isReconfigurable(const ParameterInfo& row) {
  return row.stage == Stage::Similarity || row.stage == Stage::Stopping ||
         row.stage == Stage::Boundary;
}

namespace {

/** \brief A reconfigurable optional extension whose range leaves out 0. dynamic_reconfigure
 * holds numbers only, and writes them to the parameter server too: there 0 stands for off.
 * Elsewhere off is spelt off (or false, as YAML reads off), as in the table. */
bool zeroIsOff(const ParameterInfo& row) {
  if (!isReconfigurable(row) || row.off_word.empty() ||
      (row.kind != ValueKind::Integer && row.kind != ValueKind::Real))
    return false;
  const bool above_lo = row.lo_open ? 0 > row.lo : 0 >= row.lo;
  const bool below_hi = row.hi_open ? 0 < row.hi : 0 <= row.hi;
  return !(above_lo && below_hi);
}

bool wrongKind(const ParameterInfo& row, const Value& value, std::string* why) {
  if (why)
    *why = row.name + " must be " + row.range + ", got " + value.describe();
  return false;
}

} // namespace

bool valueText(const ParameterInfo& row, const Value& value, std::string& text, std::string* why) {
  const bool boolean = row.kind == ValueKind::Boolean || row.kind == ValueKind::Switch;
  switch (value.type) {
  case Value::Type::Boolean:
    if (boolean)
      text = value.boolean ? "on" : "off";
    else if (!row.off_word.empty() && !value.boolean)
      text = row.off_word;
    else
      return wrongKind(row, value, why);
    return true;
  case Value::Type::Integer:
  case Value::Type::Real: {
    if (boolean || row.kind == ValueKind::Choice)
      return wrongKind(row, value, why);
    const bool integer = value.type == Value::Type::Integer;
    if (zeroIsOff(row) && (integer ? value.integer == 0 : value.real == 0.0))
      text = row.off_word;
    else
      text = integer ? std::to_string(value.integer) : pcl_ncut_seg::formatNumber(value.real);
    return true;
  }
  case Value::Type::Text:
    text = value.text;
    return true;
  }
  return wrongKind(row, value, why);
}

bool setFromValue(pcl_ncut_seg::Parameters& params, const ParameterInfo& row, const Value& value,
                  std::string* why) {
  std::string text;
  return valueText(row, value, text, why) && row.set(params, text, why);
}

Value typedValue(const ParameterInfo& row, const pcl_ncut_seg::Parameters& params) {
  const std::string text = row.get(params);
  const bool off = !row.off_word.empty() && text == row.off_word;
  switch (row.kind) {
  case ValueKind::Integer:
    return Value::ofInteger(off ? 0 : std::strtoll(text.c_str(), nullptr, 10));
  case ValueKind::Real:
    return Value::ofReal(off ? 0.0 : std::strtod(text.c_str(), nullptr));
  case ValueKind::Boolean:
  case ValueKind::Switch:
    return Value::ofBoolean(text == "on");
  case ValueKind::Choice:
    break;
  }
  return Value::ofText(text);
}

} // namespace pcl_ncut_seg_ros
