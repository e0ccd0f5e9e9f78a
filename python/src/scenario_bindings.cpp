/// Scenarios between Python and C++. A scenario built from Python data (dicts, lists, numbers, text) is
/// written as YAML text by yaml-cpp's emitter and read by the same reader as a file, so that a dict and a
/// file with the same keys give the same scenario and the same messages (without line numbers for a dict).

#include <cmath>
#include <regex>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <yaml-cpp/yaml.h>

#include "bindings.hpp"
#include "nodus/scenario/fingerprint.hpp"
#include "nodus/scenario/validate.hpp"
#include "nodus/scenario/yaml_reader.hpp"
#include "nodus/simulation/simulation.hpp"

namespace py = pybind11;

namespace nodus::python {
namespace {

[[noreturn]] void data_error(const std::string& where, const std::string& expected, py::handle got) {
  throw scenario::ScenarioError(fmt::format(
      "{}: {}: expected {}, got {} ({})", kDataLabel, where.empty() ? "top level" : where, expected,
      std::string(py::str(py::repr(got))), std::string(py::str(got.get_type().attr("__name__")))));
}

/// Whether the reader would take plain text `text` for something else than text (a number, a bool, null):
/// such text is written quoted.
bool reads_as_non_text(const std::string& text) {
  static const std::regex other(R"(^([-+0-9.eE]*|true|True|TRUE|false|False|FALSE|~|null|Null|NULL)$)");
  return std::regex_match(text, other);
}

bool is_scalar_list(py::handle list) {
  for (py::handle item : list)
    if (py::isinstance<py::dict>(item) || py::isinstance<py::list>(item) || py::isinstance<py::tuple>(item))
      return false;
  return true;
}

constexpr int kMaxDepth = 32;
void emit(YAML::Emitter& out, py::handle value, const std::string& where, int depth);

/// Whether a dict is written on one line, in flow style ({at: 0.5, translation: [1, 0, 0]}): when its values
/// are scalars or lists of scalars and the line stays within kFlowWidth characters, as a person would write
/// it.
constexpr std::size_t kFlowWidth = 100;
bool fits_one_line(py::handle dict, const std::string& where) {
  for (auto item : py::reinterpret_borrow<py::dict>(dict)) {
    py::handle v = item.second;
    if (py::hasattr(v, "tolist") && !py::isinstance<py::str>(v)) return false;
    if (py::isinstance<py::dict>(v)) return false;
    if ((py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) && !is_scalar_list(v)) return false;
  }
  YAML::Emitter line;
  line << YAML::Flow;
  line << YAML::BeginMap;
  for (auto [key, item] : py::reinterpret_borrow<py::dict>(dict)) {
    if (!py::isinstance<py::str>(key)) return false;
    line << YAML::Key << key.cast<std::string>() << YAML::Value;
    emit(line, item, where, 0);
  }
  line << YAML::EndMap;
  return line.good() && line.size() <= kFlowWidth;
}

/// Emits Python data as YAML: dicts as block maps (text keys), lists and tuples as sequences (flow style when
/// they hold only scalars, as [x, y, z]), bool as true/false, int as is, float as Python's shortest repr
/// that reads back to the same double, None as null, text as a string (quoted by the emitter where YAML
/// would read it otherwise). numpy arrays and scalars go through tolist() / item().
void emit(YAML::Emitter& out, py::handle value, const std::string& where, int depth) {
  // A scenario nests a few levels (branches[].stages[].motions.NAME.keyframes[].rotation); deeper data is a
  // mistake, such as a list that contains itself.
  if (depth > kMaxDepth)
    data_error(where, fmt::format("data nested at most {} levels deep", kMaxDepth), value);
  if (py::hasattr(value, "tolist") && !py::isinstance<py::str>(value)) {
    emit(out, value.attr("tolist")(), where, depth + 1);
    return;
  }
  if (py::isinstance<py::dict>(value)) {
    if (fits_one_line(value, where)) out << YAML::Flow;
    out << YAML::BeginMap;
    for (auto [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key)) data_error(where, "a key name (str)", key);
      const std::string name = key.cast<std::string>();
      out << YAML::Key << name << YAML::Value;
      emit(out, item, where.empty() ? name : where + "." + name, depth + 1);
    }
    out << YAML::EndMap;
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    if (is_scalar_list(value)) out << YAML::Flow;
    out << YAML::BeginSeq;
    int i = 0;
    for (py::handle item : value) emit(out, item, fmt::format("{}[{}]", where, i++), depth + 1);
    out << YAML::EndSeq;
  } else if (py::isinstance<py::bool_>(value)) {
    out << (value.cast<bool>() ? "true" : "false");
  } else if (py::isinstance<py::int_>(value)) {
    out << std::string(py::str(value));
  } else if (py::isinstance<py::float_>(value)) {
    const double x = value.cast<double>();
    if (!std::isfinite(x)) data_error(where, "a finite number", value);
    out << std::string(py::str(py::repr(value)));
  } else if (py::isinstance<py::str>(value)) {
    const std::string text = value.cast<std::string>();
    if (reads_as_non_text(text)) out << YAML::DoubleQuoted;
    out << text;
  } else if (value.is_none()) {
    out << YAML::Null;
  } else if (py::hasattr(value, "item")) {
    emit(out, value.attr("item")(), where, depth + 1);
  } else {
    data_error(where, "a dict, list, number, bool, str or None", value);
  }
}

/// A YAML node as Python data, plain scalars typed as the reader types them (yaml_reader.hpp): integers,
/// then numbers, then true/false and null; everything else (and every quoted scalar) is text.
py::object to_python(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      py::dict d;
      for (const auto& item : node) d[py::str(item.first.Scalar())] = to_python(item.second);
      return d;
    }
    case YAML::NodeType::Sequence: {
      py::list l;
      for (const auto& item : node) l.append(to_python(item));
      return l;
    }
    case YAML::NodeType::Scalar: {
      if (scenario::is_plain_scalar(node)) {
        const std::string& text = node.Scalar();
        if (const auto i = scenario::parse_integer(node)) return py::int_(*i);
        if (const auto x = scenario::parse_number(node)) return py::float_(*x);
        if (text == "true" || text == "True" || text == "TRUE") return py::bool_(true);
        if (text == "false" || text == "False" || text == "FALSE") return py::bool_(false);
        if (text == "~" || text == "null" || text == "Null" || text == "NULL") return py::none();
      }
      return py::str(node.Scalar());
    }
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return py::none();
  }
  return py::none();
}

/// YAML text of Python data (block style, one key per line).
std::string to_yaml_text(py::handle data) {
  if (!py::isinstance<py::dict>(data)) data_error("", "a dict of the scenario's sections", data);
  YAML::Emitter out;
  out.SetIndent(2);
  emit(out, data, "", 0);
  if (!out.good()) throw std::runtime_error("could not write the scenario as YAML: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

/// The reader's message for YAML text written from Python data, without the line numbers of that text,
/// which the user never saw: "<dict>:12: beams[0].radius: ..." becomes "<dict>: beams[0].radius: ...".
std::string drop_line(const std::string& message) {
  static const std::regex line_prefix("^<dict>:[0-9]+: ");
  return std::regex_replace(message, line_prefix, "<dict>: ", std::regex_constants::format_first_only);
}

ScenarioHandle from_data(py::handle data) {
  const std::string text = to_yaml_text(data);
  return std::make_shared<scenario::Scenario>(scenario::parse_scenario(text, kDataLabel));
}

}  // namespace

void bind_scenario(py::module_& m) {
  // ScenarioError as a ValueError; a message about a scenario built from data (by the reader, by validate, by
  // the model or by run) loses the line numbers of the YAML text generated from the data (drop_line).
  static py::exception<scenario::ScenarioError> error(m, "ScenarioError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const scenario::ScenarioError& e) {
      error(drop_line(e.what()).c_str());
    }
  });

  py::class_<scenario::Scenario, std::shared_ptr<scenario::Scenario>>(
      m, "_Scenario", "A scenario as the C++ reader holds it.")
      .def_property_readonly("path", [](const scenario::Scenario& s) { return s.path; })
      .def_property_readonly("beams",
                             [](const scenario::Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& b : s.beams) names.push_back(b.name);
                               return names;
                             })
      .def_property_readonly("conditions",
                             [](const scenario::Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& c : s.conditions) names.push_back(c.name);
                               return names;
                             })
      .def_property_readonly("stages",
                             [](const scenario::Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& st : s.stages) names.push_back(st.name);
                               return names;
                             })
      .def_property_readonly("branches",
                             [](const scenario::Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& b : s.branches) names.push_back(b.name);
                               return names;
                             })
      .def(
          "validate",
          [](const scenario::Scenario& s) {
            py::gil_scoped_release release;
            scenario::validate(s);
            const simulation::Simulation sim(s);  // the checks of the model (as `nodus check`)
          },
          "Every check of the reader and of the model (as `nodus check`); raises ScenarioError.")
      .def("describe", &scenario::describe, "The resolved settings, as `nodus check` prints them.")
      .def(
          "canonical_text",
          [](const scenario::Scenario& s) {
            return scenario::state_fingerprint_text(s, static_cast<int>(s.stages.size()));
          },
          "Every value that shapes the results, one KEY = VALUE per line (the checkpoints' fingerprint).");

  m.def(
      "read_file",
      [](const std::string& path) {
        return std::make_shared<scenario::Scenario>(scenario::read_scenario(path));
      },
      py::arg("path"), "Reads and checks a scenario file.");
  m.def(
      "parse_text",
      [](const std::string& text, const std::string& label) {
        return std::make_shared<scenario::Scenario>(scenario::parse_scenario(text, label));
      },
      py::arg("text"), py::arg("label"), "Reads and checks YAML text; `label` names it in messages.");
  m.def(
      "from_data", [](py::handle data) { return from_data(data); }, py::arg("data"),
      "Reads and checks a scenario given as Python data (a dict with the YAML's keys).");
  m.def("data_to_yaml", &to_yaml_text, py::arg("data"), "YAML text of a scenario given as Python data.");
  m.def(
      "yaml_to_data",
      [](const std::string& text) {
        YAML::Node root;
        try {
          root = YAML::Load(text);
        } catch (const YAML::Exception& e) {
          throw scenario::ScenarioError(fmt::format("YAML: expected valid YAML, got {}", e.msg));
        }
        return to_python(root);
      },
      py::arg("text"), "Python data of YAML text, scalars typed as the scenario reader types them.");
  m.def("keys_markdown", &scenario::scenario_keys_markdown, "The table of scenario keys (as `nodus keys`).");
}

}  // namespace nodus::python
