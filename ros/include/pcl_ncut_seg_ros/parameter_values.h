/*
 * pcl_ncut_seg ROS: the parameters of parameter_table.h as ROS holds them. The parameter
 * server and dynamic_reconfigure keep typed values (int, double, bool, string); the table reads
 * text. One name everywhere: a private parameter ~k or ~boundary_band is the table's row k or
 * boundary_band. No ROS here, so that the build's .cfg writer and the tests use it too.
 */
#pragma once

#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/parameters.h>

#include <string>

namespace pcl_ncut_seg_ros {

/** \brief A value as the parameter server or dynamic_reconfigure holds it. */
struct Value {
  enum class Type { Integer, Real, Boolean, Text };
  Type type = Type::Text;
  long long integer = 0;
  double real = 0;
  bool boolean = false;
  std::string text;

  static Value ofInteger(long long v);
  static Value ofReal(double v);
  static Value ofBoolean(bool v);
  static Value ofText(std::string v);
  /** \brief As the user wrote it, for messages ("0.7", "true", "'auto'"). */
  std::string describe() const;
};

/** \brief The rows that dynamic_reconfigure sets: those of the cut stages (similarity,
 * stopping, boundary), which re-cut a kept analysis. */
bool isReconfigurable(const pcl_ncut_seg::ParameterInfo& row);

/** \brief The table's text for a value of this row: a number in its shortest decimal, a bool
 * as on or off. For an optional extension (a row with an off word), false means off too
 * ("~boundary_band: off" reads as false in YAML); for a reconfigurable one whose range leaves
 * out 0, so does 0, as dynamic_reconfigure has no words for numbers (the only place 0 means
 * off). False with why when the value is of no kind the row takes. */
bool valueText(const pcl_ncut_seg::ParameterInfo& row, const Value& value, std::string& text,
               std::string* why);

/** \brief Set the row from the value through the table; false (params unchanged) with why
 * naming the range ("k must be an integer >= 2, got '1'"). */
bool setFromValue(pcl_ncut_seg::Parameters& params, const pcl_ncut_seg::ParameterInfo& row,
                  const Value& value, std::string* why);

/** \brief The row's value in params as dynamic_reconfigure holds it: an integer, a real, a
 * bool, or a choice's word; an optional extension that is off is 0. */
Value typedValue(const pcl_ncut_seg::ParameterInfo& row, const pcl_ncut_seg::Parameters& params);

} // namespace pcl_ncut_seg_ros
