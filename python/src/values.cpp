#include "values.h"

#include <pybind11/stl.h>

#include <cstdlib>

namespace pcl_ncut_seg_python {

using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::Parameters;
using pcl_ncut_seg::ValueKind;

namespace {

bool isBool(const py::handle& value) {
  if (py::isinstance<py::bool_>(value))
    return true;
  // numpy.bool_ is no subclass of bool.
  const py::object numpy_bool = py::module_::import("numpy").attr("bool_");
  return py::isinstance(value, numpy_bool);
}

const char* kindName(ValueKind kind) {
  switch (kind) {
  case ValueKind::Integer:
    return "integer";
  case ValueKind::Real:
    return "real";
  case ValueKind::Switch:
    return "switch";
  case ValueKind::Boolean:
    return "boolean";
  case ValueKind::Choice:
    return "choice";
  }
  return "";
}

/** \brief "unknown parameter 'x'", with the closest names when there are some. */
std::string unknownName(const std::string& name) {
  std::string why = "unknown parameter '" + name + "'";
  py::list names;
  for (const ParameterInfo& r : pcl_ncut_seg::parameterTable())
    names.append(r.name);
  names.append("paper");
  for (const auto& s : pcl_ncut_seg::parameterShorthands())
    names.append(s.name);
  const py::list close =
      py::module_::import("difflib").attr("get_close_matches")(name, names, 3, 0.7);
  for (std::size_t i = 0; i < close.size(); ++i)
    why += (i == 0 ? "; did you mean " : " or ") + std::string("'") + close[i].cast<std::string>() +
           "'";
  return why;
}

} // namespace

std::string valueText(const ParameterInfo& row, const py::handle& value) {
  if (value.is_none())
    return row.off_word.empty() ? "None" : row.off_word;
  if (isBool(value))
    return value.cast<bool>() ? "on" : "off";
  if (py::isinstance<py::str>(value))
    return value.cast<std::string>();
  if (py::hasattr(value, "__index__")) // int, numpy integers
    return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
  if (py::hasattr(value, "__float__")) // float, numpy floats: the shortest exact decimal
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  return py::str(value); // anything else: the table says why it is no value
}

py::object parameterObject(const ParameterInfo& row, const Parameters& params) {
  const std::string text = row.get(params);
  if (!row.off_word.empty() && text == row.off_word)
    return py::none();
  switch (row.kind) {
  case ValueKind::Integer:
    return py::int_(py::str(text));
  case ValueKind::Real:
    return py::float_(std::strtod(text.c_str(), nullptr));
  case ValueKind::Switch:
  case ValueKind::Boolean:
    return py::bool_(text == "on");
  case ValueKind::Choice:
    break;
  }
  return py::str(text);
}

void applyKeywords(Parameters& params, const py::dict& keywords) {
  Parameters p = params;
  if (keywords.contains("paper")) {
    const py::object paper = keywords["paper"];
    if (!isBool(paper))
      throw py::value_error("paper must be True or False, got " +
                            py::repr(paper).cast<std::string>());
    p = paper.cast<bool>() ? Parameters::paper() : Parameters::defaults();
    p.execution = params.execution; // how the work runs is no part of a preset
  }
  for (const auto& item : keywords) {
    const std::string name = py::str(item.first);
    if (name == "paper")
      continue;
    bool shorthand = false;
    for (const auto& s : pcl_ncut_seg::parameterShorthands())
      if (s.name == name) {
        if (!isBool(item.second) || !item.second.cast<bool>())
          throw py::value_error(name + " takes True only (" + s.help + ")");
        pcl_ncut_seg::setParameter(p, s.parameter, s.value);
        shorthand = true;
      }
    if (shorthand)
      continue;
    const ParameterInfo* row = pcl_ncut_seg::findParameter(name);
    if (!row)
      throw py::value_error(unknownName(name));
    std::string why;
    if (!row->set(p, valueText(*row, item.second), &why))
      throw py::value_error(why);
  }
  std::string why;
  if (!pcl_ncut_seg::validate(p, &why))
    throw py::value_error(why);
  params = p;
}

std::vector<const ParameterInfo*> keywordOrder() {
  // Giving segments chooses the count rule (as the tool's -segments): segments goes before
  // stopping, so that keywords in this order keep the rule they show.
  std::vector<const ParameterInfo*> rows;
  for (const ParameterInfo& r : pcl_ncut_seg::parameterTable()) {
    if (r.name == "segments")
      continue;
    if (r.name == "stopping")
      rows.push_back(pcl_ncut_seg::findParameter("segments"));
    rows.push_back(&r);
  }
  return rows;
}

py::dict parameterDict(const Parameters& params) {
  py::dict d;
  for (const ParameterInfo* r : keywordOrder())
    d[py::str(r->name)] = parameterObject(*r, params);
  return d;
}

py::list parameterTableList() {
  const Parameters defaults, paper = Parameters::paper();
  py::list out;
  for (const ParameterInfo& r : pcl_ncut_seg::parameterTable()) {
    py::dict d;
    d["name"] = r.name;
    d["field"] = r.field;
    d["stage"] = pcl_ncut_seg::stageName(r.stage);
    d["analysis"] = pcl_ncut_seg::isAnalysisStage(r.stage);
    d["kind"] = kindName(r.kind);
    d["range"] = r.range;
    d["help"] = r.help;
    d["off"] = r.off_word.empty() ? py::object(py::none()) : py::object(py::str(r.off_word));
    d["choices"] = py::cast(r.choices);
    d["default"] = parameterObject(r, defaults);
    d["paper_value"] = parameterObject(r, paper);
    d["in_paper"] = r.paper;
    out.append(d);
  }
  return out;
}

} // namespace pcl_ncut_seg_python
