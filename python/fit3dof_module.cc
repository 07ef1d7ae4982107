// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The Python module's compiled core, fit3dof._fit3dof (pybind11). The
// package fit3dof (fit3dof/__init__.py) re-exports it; see the README's
// Python section. Every long call releases the GIL, so fits run in
// parallel from Python threads; InputError becomes fit3dof.InputError, a
// ValueError carrying the message the command line prints.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fit3dof/angles.h"
#include "fit3dof/batch.h"
#include "fit3dof/config.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"
#include "fit3dof/provenance.h"
#include "fit3dof/simulator.h"
#include "fit3dof/version.h"

namespace py = pybind11;

namespace fit3dof {
namespace {

using Release = py::call_guard<py::gil_scoped_release>;

py::object JsonLoads(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// An (n, 3) array of phi, theta, psi (deg) from per-channel vectors.
py::array_t<double> Angles(const std::vector<double>& phi,
                           const std::vector<double>& theta,
                           const std::vector<double>& psi) {
  const py::ssize_t n = static_cast<py::ssize_t>(phi.size());
  py::array_t<double> out({n, py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    a(i, 0) = phi[i];
    a(i, 1) = theta[i];
    a(i, 2) = psi[i];
  }
  return out;
}

py::array_t<double> Vector(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// The computed angles of a segment (stored interleaved phi, theta, psi).
py::array_t<double> Computed(const SegmentFit& s) {
  const py::ssize_t n = s.data.size();
  py::array_t<double> out({n, py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    for (int ch = 0; ch < 3; ++ch) a(i, ch) = s.computed[3 * i + ch];
  }
  return out;
}

// computed - measured (theta - theta_m, as the report and tools/plot draw
// them), roll wrapped to +-180 deg: a whole turn is no error.
py::array_t<double> Residuals(const SegmentFit& s) {
  py::array_t<double> out = Angles(s.data.phi, s.data.theta, s.data.psi);
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      double r = s.computed[3 * i + ch] - a(i, ch);
      if (ch == 0) r -= WholeTurns(r);
      a(i, ch) = r;
    }
  }
  return out;
}

py::tuple Channels(const ChannelValues& c) {
  return py::make_tuple(c.phi, c.theta, c.psi);
}

// name -> ParameterEstimate, shared parameters and segments' own alike.
py::dict Parameters(const FitResult& r) {
  py::dict out;
  for (const ParameterEstimate& e : r.parameters) out[e.name.c_str()] = e;
  return out;
}

// The YAML text of a config as a dict would give it: YAML 1.2 reads JSON.
Case CaseFromDict(const py::dict& config, const std::string& base_dir) {
  const std::string text =
      py::module_::import("json").attr("dumps")(config).cast<std::string>();
  return ParseConfig(text, "<dict>", base_dir);
}

void SetParameter(Case* c,
                  const std::string& name,
                  py::object value,
                  py::object free) {
  const int i = FindParameter(c->model, name);
  if (i < 0) {
    const std::string hint = SuggestParameter(c->model, name);
    throw InputError("unknown parameter " + name + " of the " +
                     ModelName(c->model) + " model" +
                     (hint.empty() ? "" : " (did you mean " + hint + "?)"));
  }
  // A tied parameter given a value or a freedom of its own is untied: it
  // would otherwise silently keep following its source.
  if (!value.is_none() || !free.is_none()) c->parameters[i].tied_to = -1;
  if (!value.is_none()) {
    c->parameters[i].value = value.cast<double>();
    c->parameters[i].auto_start = false;
  }
  if (!free.is_none()) c->parameters[i].free = free.cast<bool>();
  c->SettleTies();
}

py::dict CaseParameters(const Case& c) {
  py::dict out;
  const auto& table = ParameterTable(c.model);
  for (size_t i = 0; i < table.size(); ++i) {
    const ParameterSetting& p = c.parameters[i];
    py::dict entry(py::arg("value") = p.value, py::arg("free") = p.free);
    if (p.tied()) {
      entry["tied_to"] = table[p.tied_to].name;
      entry["tie_factor"] = p.tie_factor;
    }
    out[table[i].name.c_str()] = entry;
  }
  return out;
}

py::object ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return JsonLoads(text.str());
}

}  // namespace
}  // namespace fit3dof

PYBIND11_MODULE(_fit3dof, m) {
  using namespace fit3dof;
  m.doc() = "fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion";
  m.attr("__version__") = FIT3DOF_VERSION;
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  SetCommandLine("python3: import fit3dof");

  py::class_<Case>(m, "Case", "A validated config (docs/formats.md).")
      .def_static("from_dict",
                  &CaseFromDict,
                  py::arg("config"),
                  py::arg("base_dir") = ".",
                  "A case from the config's YAML keys as a dict; relative "
                  "data paths resolve against base_dir.")
      .def_readwrite("name", &Case::name)
      .def_readonly("source", &Case::source)
      .def_property_readonly(
          "model",
          [](const Case& c) { return std::string(ModelName(c.model)); })
      .def_property_readonly("parameters",
                             &CaseParameters,
                             "name -> {'value', 'free'} (and 'tied_to', "
                             "'tie_factor' for a tied one), every parameter")
      .def("set_parameter",
           &SetParameter,
           py::arg("name"),
           py::arg("value") = py::none(),
           py::arg("free") = py::none(),
           "Sets a parameter's starting (or fixed) value and/or freedom "
           "(a tied parameter is untied).")
      .def("to_yaml", &CaseToYaml, "The config as YAML (loads back equal).")
      .def("__eq__", [](const Case& a, const Case& b) { return a == b; })
      .def("__repr__", [](const Case& c) {
        return "<fit3dof.Case " + c.name + " (" + ModelName(c.model) + ", " +
               std::to_string(c.segments.size()) + " segments)>";
      });

  py::class_<ParameterEstimate>(m, "Parameter")
      .def_readonly("name", &ParameterEstimate::name)
      .def_readonly("segment", &ParameterEstimate::segment)
      .def_readonly("value", &ParameterEstimate::value)
      .def_readonly("standard_error", &ParameterEstimate::standard_error)
      .def_readonly("rms_error", &ParameterEstimate::rms_error)
      .def_readonly("units", &ParameterEstimate::units)
      .def_readonly("free", &ParameterEstimate::free)
      .def_readonly("tied_to", &ParameterEstimate::tied_to)
      .def_readonly("tie_factor", &ParameterEstimate::tie_factor)
      .def("__repr__", [](const ParameterEstimate& e) {
        std::ostringstream out;
        out.precision(6);
        out << "<" << e.name << " = " << e.value;
        if (e.free || !e.tied_to.empty()) out << " +- " << e.standard_error;
        if (!e.tied_to.empty()) {
          out << " (tied: " << e.tie_factor << " x " << e.tied_to << ")";
        }
        out << (e.units.empty() ? "" : " ") << e.units << ">";
        return out.str();
      });

  py::class_<SegmentFit>(m, "Segment")
      .def_readonly("name", &SegmentFit::name)
      .def_property_readonly(
          "times", [](const SegmentFit& s) { return Vector(s.data.t); })
      .def_property_readonly(
          "measured",
          [](const SegmentFit& s) {
            return Angles(s.data.phi, s.data.theta, s.data.psi);
          },
          "(n, 3) phi, theta, psi as fitted (deg)")
      .def_property_readonly("computed", &Computed, "(n, 3), deg")
      .def_property_readonly(
          "residuals", &Residuals, "(n, 3) computed - measured, deg")
      .def_property_readonly(
          "rms_residual_deg",
          [](const SegmentFit& s) { return Channels(s.rms_residual_deg); })
      .def_property_readonly("sigma_deg", [](const SegmentFit& s) {
        return Channels(s.sigma_deg);
      });

  py::class_<FitResult>(m, "FitResult")
      .def_readonly("name", &FitResult::name)
      .def_property_readonly(
          "model",
          [](const FitResult& r) { return std::string(ModelName(r.model)); })
      .def_readonly("converged", &FitResult::converged)
      .def_readonly("termination", &FitResult::termination)
      .def_readonly("iterations", &FitResult::iterations)
      .def_readonly("points", &FitResult::points)
      .def_readonly("free_parameters", &FitResult::free_parameters)
      .def_readonly("probable_error", &FitResult::probable_error)
      .def_readonly("warnings", &FitResult::warnings)
      .def_readonly("adequacy", &FitResult::adequacy)
      .def_readonly("segments", &FitResult::segments)
      .def_property_readonly("parameters",
                             &Parameters,
                             "name -> Parameter (value, standard_error, "
                             "rms_error, units, free)")
      .def_property_readonly(
          "process_noise",
          [](const FitResult& r) {
            py::dict out;
            for (const ProcessNoiseEstimate& e : r.process_noise) {
              py::dict axis;
              axis["intensity"] = e.intensity;
              axis["standard_error"] = e.standard_error;
              axis["estimated"] = e.estimated;
              out[py::str(e.axis)] = axis;
            }
            return out;
          },
          "solver.method filter_error: axis -> {intensity (deg/s^1.5), "
          "standard_error, estimated}")
      .def(
          "to_dict",
          [](const FitResult& r) { return JsonLoads(ReportJson(r)); },
          "report.json as a dict")
      .def("write",
           &WriteFitOutputs,
           py::arg("out_dir"),
           Release(),
           "report.json and fit.csv into out_dir (as `fit3dof fit`)")
      .def("__repr__", [](const FitResult& r) {
        return "<fit3dof.FitResult " + r.name +
               (r.converged ? " converged" : " not converged") +
               ", probable error " + std::to_string(r.probable_error) + ">";
      });

  py::class_<Diagnosis>(m, "Diagnosis")
      .def_property_readonly(
          "verdict",
          [](const Diagnosis& d) { return VerdictToString(d.verdict); })
      .def_readonly("verdict_text", &Diagnosis::verdict_text)
      .def_property_readonly("effects_added",
                             [](const Diagnosis& d) {
                               std::vector<std::string> ids;
                               for (const auto& s : d.steps)
                                 ids.push_back(s.effect);
                               return ids;
                             })
      .def_readonly("final_case", &Diagnosis::final_case)
      .def_readonly(
          "fits",
          &Diagnosis::fits,
          "the nominal fit, then one per step taken (kept, partial "
          "or pruned), then one per pruning, then after a tie those of "
          "the alternatives and of the model without it (none with a "
          "stand-in); final_fit "
          "is the "
          "final model's")
      .def_property_readonly("final_fit",
                             [](const Diagnosis& d) { return d.FinalFit(); })
      .def(
          "to_dict",
          [](const Diagnosis& d, const Case& c) {
            return JsonLoads(DiagnosisJson(d, c));
          },
          py::arg("case"),
          "diagnosis.json as a dict");

  m.def(
      "load_config",
      [](const std::string& path) { return LoadConfig(path); },
      py::arg("path"),
      Release(),
      "Reads and validates a YAML config; InputError (a ValueError) names "
      "the file, line and key of a problem.");
  m.def("fit",
        &Fit,
        py::arg("case"),
        Release(),
        "Fits the case's data (as `fit3dof fit`).");
  m.def(
      "simulate",
      [](const Case& c, std::optional<std::vector<double>> times) {
        TimeHistory h;
        {
          py::gil_scoped_release release;
          h = times ? SimulateAt(c, c.Values(), *times) : Simulate(c);
        }
        py::array_t<double> out({py::ssize_t{h.size()}, py::ssize_t{4}});
        auto a = out.mutable_unchecked<2>();
        for (int i = 0; i < h.size(); ++i) {
          a(i, 0) = h.t[i];
          a(i, 1) = h.phi[i];
          a(i, 2) = h.theta[i];
          a(i, 3) = h.psi[i];
        }
        return out;
      },
      py::arg("case"),
      py::arg("times") = py::none(),
      "The motion the case's parameters give: an (n, 4) array of t, phi, "
      "theta, psi (deg), the columns `fit3dof simulate` writes. At `times` "
      "(initial conditions at times[0], no noise), or without them at the "
      "case's simulate: times with its noise, as `fit3dof simulate`.");
  m.def(
      "diagnose",
      [](const Case& c,
         const std::vector<std::string>& absent,
         bool exact_step) {
        DiagnoseOptions options;
        options.absent = absent;
        options.coarse_search = !exact_step;
        return Diagnose(c, options);
      },
      py::arg("case"),
      py::arg("absent") = std::vector<std::string>(),
      py::arg("exact_step") = false,
      Release(),
      "Finds, names and adds missing effects; `absent`: catalog effect ids "
      "known absent, never tried (InputError for any other id); "
      "`exact_step`: every fit at the config's solver.step (by default the "
      "search integrates at the coarsest step within 0.1 of each value's "
      "error of it; to_dict's search_step).");
  m.def(
      "batch",
      [](const std::string& manifest,
         const std::string& out_dir,
         int jobs,
         bool resume) {
        {
          py::gil_scoped_release release;
          BatchOptions options;
          options.out_dir = out_dir;
          options.jobs = jobs;
          options.resume = resume;
          options.progress = false;
          RunBatch(manifest, options);
        }
        return ReadJsonFile(out_dir + "/summary.json");
      },
      py::arg("manifest"),
      py::arg("out_dir"),
      py::arg("jobs") = 0,
      py::arg("resume") = false,
      "Runs a campaign (as `fit3dof batch`); returns summary.json as a dict.");
}
