/*
 * pcl_ncut_seg ROS: writes the dynamic_reconfigure .cfg of the nodelet from parameterTable():
 * one entry per row of a cut stage (similarity, stopping, boundary), with the row's name,
 * default, range and help. The build runs it, then dynamic_reconfigure's generator on its
 * output, so the reconfigurable parameters are the table's.
 *
 *   pcl_ncut_seg_write_cfg OUTPUT.cfg
 */
#include <pcl_ncut_seg_ros/parameter_values.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace {

using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::ValueKind;
using pcl_ncut_seg_ros::Value;

/** \brief A Python string literal (dynamic_reconfigure allows no quotes in descriptions). */
std::string quoted(std::string text) {
  for (std::size_t at = text.find('\''); at != std::string::npos; at = text.find('\''))
    text.replace(at, 1, "\u2019");
  for (std::size_t at = text.find('"'); at != std::string::npos; at = text.find('"'))
    text.replace(at, 1, "\u201d");
  std::string out = "\"";
  for (char c : text)
    out += c == '\\' ? std::string("\\\\") : std::string(1, c);
  return out + "\"";
}

/** \brief A number as Python reads it (finite bounds only). */
std::string number(double v) {
  return pcl_ncut_seg::formatNumber(v);
}

void writeRow(std::ostream& out, const ParameterInfo& row,
              const pcl_ncut_seg::Parameters& defaults) {
  const Value value = pcl_ncut_seg_ros::typedValue(row, defaults);
  std::string description =
      "[" + std::string(pcl_ncut_seg::stageName(row.stage)) + "] " + row.help + "; " + row.range;
  if (!row.off_word.empty())
    description += " (0: " + row.off_word + ")";
  switch (value.type) {
  case Value::Type::Boolean:
    out << "gen.add(" << quoted(row.name) << ", bool_t, 1, " << quoted(description) << ", "
        << (value.boolean ? "True" : "False") << ")\n";
    return;
  case Value::Type::Text: {
    // A choice: an enum of its words, each a constant named row_word.
    out << row.name << "_enum = gen.enum([";
    for (std::size_t i = 0; i < row.choices.size(); ++i)
      out << (i ? ", " : "") << "gen.const(" << quoted(row.name + "_" + row.choices[i])
          << ", str_t, " << quoted(row.choices[i]) << ", " << quoted(row.choices[i]) << ")";
    out << "], " << quoted(row.name) << ")\n";
    out << "gen.add(" << quoted(row.name) << ", str_t, 1, " << quoted(description) << ", "
        << quoted(value.text) << ", edit_method=" << row.name << "_enum)\n";
    return;
  }
  case Value::Type::Integer:
  case Value::Type::Real: {
    const bool integer = value.type == Value::Type::Integer;
    out << "gen.add(" << quoted(row.name) << ", " << (integer ? "int_t" : "double_t") << ", 1, "
        << quoted(description) << ", "
        << (integer ? std::to_string(value.integer) : number(value.real));
    // An open lower bound is the slider's end: the nodelet rejects it (or reads 0 as off).
    if (std::isfinite(row.lo))
      out << ", min=" << number(row.lo);
    if (std::isfinite(row.hi))
      out << ", max=" << number(row.hi);
    out << ")\n";
    return;
  }
  }
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: pcl_ncut_seg_write_cfg OUTPUT.cfg\n";
    return 2;
  }
  std::ostringstream out;
  out << "#!/usr/bin/env python3\n"
      << "# Written by pcl_ncut_seg_write_cfg from pcl_ncut_seg::parameterTable() (the rows of\n"
      << "# the cut stages); do not edit.\n"
      << "PACKAGE = \"pcl_ncut_seg\"\n"
      << "from dynamic_reconfigure.parameter_generator_catkin import *\n"
      << "gen = ParameterGenerator()\n";
  const pcl_ncut_seg::Parameters defaults;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (pcl_ncut_seg_ros::isReconfigurable(row))
      writeRow(out, row, defaults);
  out << "exit(gen.generate(PACKAGE, \"pcl_ncut_seg\", \"SupernodeNCutSegmentation\"))\n";
  std::ofstream file(argv[1]);
  file << out.str();
  if (!file) {
    std::cerr << "pcl_ncut_seg_write_cfg: cannot write " << argv[1] << "\n";
    return 1;
  }
  return 0;
}
