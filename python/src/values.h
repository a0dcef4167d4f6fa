/*
 * pcl_ncut_seg Python module: parameters by the names of the table in
 * pcl_ncut_seg/parameter_table.h. A Python value becomes the table's text (None: the row's
 * off word, bool: "on"/"off", int: its digits, float: repr, str: as is) and the table parses
 * and checks it, so that the module accepts exactly what the tools' flags accept and rejects
 * the rest with the library's reason.
 */
#pragma once

#include <pybind11/pybind11.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <string>
#include <vector>

namespace pcl_ncut_seg_python {

namespace py = pybind11;

/** \brief The table's text for a Python value given to this parameter. */
std::string valueText(const pcl_ncut_seg::ParameterInfo& row, const py::handle& value);

/** \brief The parameter's value as a Python object: None (off or auto), bool, int, float or
 * str. */
py::object parameterObject(const pcl_ncut_seg::ParameterInfo& row,
                           const pcl_ncut_seg::Parameters& params);

/** \brief Apply keyword parameters in their order: paper=True or False first picks the preset
 * everything else starts from (Parameters::paper() or the defaults; the threads are kept),
 * a tool shorthand (exact=True) sets its parameter, any other keyword is a row's name. All or
 * nothing: throws py::value_error with the library's reason and leaves params unchanged on a
 * bad name or value. */
void applyKeywords(pcl_ncut_seg::Parameters& params, const py::dict& keywords);

/** \brief The rows in the table's order but for segments, which comes before stopping:
 * keywords in this order set what they show (segments alone would choose the count rule). */
std::vector<const pcl_ncut_seg::ParameterInfo*> keywordOrder();

/** \brief {name: value} for every row, in keywordOrder(). */
py::dict parameterDict(const pcl_ncut_seg::Parameters& params);

/** \brief The table as a list of dicts (name, field, stage, kind, range, help, default,
 * paper_value, in_paper, analysis). */
py::list parameterTableList();

} // namespace pcl_ncut_seg_python
