// cranesim._core: the library's session for Python (python/cranesim/). The Python layer only
// adapts: scenes from dicts, inputs by name, numpy arrays; the logic is the C++ Session's.

#include <fmt/format.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <future>

#include "cranesim/control/crane_sway.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/control/sway_axis.hpp"
#include "cranesim/io/modes_writer.hpp"
#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/session/session.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/study/study.hpp"
#include "cranesim/study/study_command.hpp"
#include "cranesim/version.hpp"

namespace nb = nanobind;
using namespace cranesim;

namespace {

/// Simulated seconds beyond which an advance runs where Ctrl-C can stop it (a thread's start,
/// tens of microseconds, is then small beside the integration).
constexpr double kInterruptibleAdvance = 1.0;

using Vector = nb::ndarray<nb::numpy, double, nb::shape<-1>>;
using Commands = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

/// A numpy array that owns a copy of `values`.
Vector vector(const double* values, std::size_t n) {
  double* data = new double[n];
  std::copy(values, values + n, data);
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return Vector(data, {n}, owner);
}

Vector vector(const Vec3& v) { return vector(v.data(), 3); }

/// Raises cranesim.SceneError(file, path, line, message) for a scene error in `file`.
[[noreturn]] void raiseSceneError(const std::string& file, const SceneError& e) {
  const nb::object type = nb::module_::import_("cranesim.errors").attr("SceneError");
  const nb::object error = type(file, e.where().path, e.where().line, std::string(e.what()));
  PyErr_SetObject(type.ptr(), error.ptr());
  throw nb::python_error();
}

/// What `read` returns, a scene error in `file` raised as cranesim.SceneError.
template <class Read> auto read(const std::string& file, const Read& read) -> decltype(read()) {
  try {
    return read();
  } catch (const SceneError& e) {
    raiseSceneError(file, e);
  }
}

/// `work(stop)` run on a thread of its own while this one waits without Python's lock and
/// checks for signals: Ctrl-C sets `stop` (the work ends at its next step, as a signal ends the
/// command line's run), waits for the work to end, and raises KeyboardInterrupt.
template <class Work> auto interruptibly(const Work& work) {
  std::atomic<bool> stop{false};
  auto done = std::async(std::launch::async, [&] { return work(stop); });
  for (;;) {
    {
      nb::gil_scoped_release released;
      if (done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready) break;
    }
    if (PyErr_CheckSignals() != 0) {
      stop = true;
      {
        nb::gil_scoped_release released;
        done.wait();
      }
      throw nb::python_error();
    }
  }
  return done.get();
}

/// The scene file at `path`, or the YAML `text` standing for a file called `name`, drawn where its
/// equilibrium meets the figures it states.
Scene scene(const std::string& path, const std::string& text, const std::string& name) {
  return read(path.empty() ? name : path, [&] {
    return sceneAtStatedEquilibrium(path.empty() ? parseScene(text, name) : readScene(path), true);
  });
}

/// The scene's static equilibrium (its solver.statics method), written to `out` as a one-sample
/// results file as `crane-sim static` writes it; returns why it is unstable (empty when stable).
std::string writeStatic(const Scene& scene, const std::string& out) {
  const Model model = read(scene.path, [&] { return compileModel(scene); });
  const Assembler assembler(model);
  nb::gil_scoped_release released;
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
  const std::string unstable = equilibriumInstability(model, eq, true);
  writeEquilibriumResults(out, assembler, eq, scene.path, scene.text, unstable);
  return unstable;
}

/// The `count` lowest small-vibration modes about the equilibrium (0: all), written to `out` as
/// `crane-sim modes` writes them.
void writeModesFile(const Scene& scene, int count, const std::string& out) {
  const Model model = read(scene.path, [&] { return compileModel(scene); });
  const Assembler assembler(model);
  nb::gil_scoped_release released;
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
  const ModalResult modal = computeModes(model, eq.q, eq.t, count);
  writeModes(out, model, eq.q, modal, {scene.path, scene.text, eq.t, {}});
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() = "cranesim's engine: a scene's run driven step by step (cranesim.Simulation wraps it).";
  m.attr("__version__") = std::string(kVersion);

  nb::class_<SimulationState>(m, "State", "A run's state, saved to go on from later (Simulation.save_state).")
      .def_prop_ro("time", [](const SimulationState& s) { return s.t; }, "The time it was saved at, s.")
      .def("__repr__", [](const SimulationState& s) { return "<cranesim.State at t = " + std::to_string(s.t) + " s>"; });

  nb::class_<Session>(m, "Session", "A run of a compiled scene, advanced by its caller (cranesim.Simulation).")
      .def_static(
          "open",
          [](const std::string& path, const std::string& text, const std::string& name, bool record) {
            const Scene s = scene(path, text, name);
            return read(s.path, [&] { return new Session(s, record); });
          },
          nb::arg("path"), nb::arg("text"), nb::arg("name"), nb::arg("record"), nb::rv_policy::take_ownership,
          "Reads, compiles and starts the scene file at `path`, or when `path` is empty the scene given as YAML "
          "`text` (`name` stands for its file in messages); with `record`, keeps its samples.")
      .def_prop_ro("recording", &Session::recording)
      .def("write_results", &Session::writeResults, nb::arg("path"),
           "Writes the samples so far as a results file, as `crane-sim run` writes it.")
      .def_prop_ro("name", [](const Session& s) { return s.model().name; })
      .def_prop_ro("time", &Session::time)
      .def_prop_ro("t_end", [](const Session& s) { return s.model().solver.t_end; })
      .def_prop_ro("input_names", [](const Session& s) { return namesOf(s.model().inputs); })
      .def_prop_ro("input_kinds",
                   [](const Session& s) {
                     std::vector<std::string> kinds;
                     for (const ModelInput& input : s.model().inputs) kinds.push_back(input.what);
                     return kinds;
                   })
      .def("input_limits",
           [](const Session& s, int index) {
             const InputSpec& spec = s.model().inputs.at(static_cast<std::size_t>(index)).signal->spec();
             const double limits[] = {spec.max_speed, spec.max_acceleration, spec.min, spec.max};
             return vector(limits, 4);
           },
           nb::arg("index"), "[speed, acceleration, min, max] of input `index` (inf where none).")
      .def("input_command_is_speed",
           [](const Session& s, int index) {
             return s.model().inputs.at(static_cast<std::size_t>(index)).signal->spec().command == InputCommand::Speed;
           },
           nb::arg("index"))
      .def("input", &Session::input, nb::arg("name"), "The index of the input named `name`.")
      .def("joint", &Session::joint, nb::arg("name"), "The index of the joint named `name`.")
      .def("set_inputs",
           [](Session& s, Commands commands) {
             const std::size_t n = s.model().inputs.size();
             if (commands.shape(0) != n)
               throw std::invalid_argument("set_inputs takes " + std::to_string(n) + " commands, one per input, not " +
                                           std::to_string(commands.shape(0)));
             for (std::size_t k = 0; k < n; ++k)
               if (!std::isfinite(commands(k)))
                 throw std::invalid_argument(fmt::format("input '{}': the command is {}, not a finite number",
                                                         s.model().inputs[k].name, commands(k)));
             std::vector<double> held(n);
             for (std::size_t k = 0; k < n; ++k) held[k] = s.setInput(static_cast<int>(k), commands(k));
             return vector(held.data(), n);
           },
           nb::arg("commands"),
           "Holds one command per input from now on; returns them as held (clipped to the limits). A command that "
           "is not finite raises ValueError naming its input and changes nothing.")
      .def("set_input", &Session::setInput, nb::arg("index"), nb::arg("command"))
      .def("input_values",
           [](const Session& s) {
             std::vector<double> v(s.model().inputs.size());
             for (std::size_t k = 0; k < v.size(); ++k) v[k] = s.inputValue(static_cast<int>(k));
             return vector(v.data(), v.size());
           })
      .def("input_rates",
           [](const Session& s) {
             std::vector<double> v(s.model().inputs.size());
             for (std::size_t k = 0; k < v.size(); ++k) v[k] = s.inputRate(static_cast<int>(k));
             return vector(v.data(), v.size());
           })
      .def("advance_to",
           [](Session& s, double t) {
             if (t - s.time() > kInterruptibleAdvance)
               return interruptibly([&](const std::atomic<bool>& stop) { return s.advanceTo(t, &stop); });
             nb::gil_scoped_release released;
             return s.advanceTo(t);
           },
           nb::arg("t"),
           "Integrates to time t; False once the run has stopped (at t_end, or `message` says why). Ctrl-C during a "
           "long advance ends the run, marked interrupted, and raises KeyboardInterrupt.")
      .def("reset", &Session::reset, "Back to the starting state, every input at rest.")
      .def("save", &Session::save, "The run's state now; the integrator restarts here.")
      .def("restore", &Session::restore, nb::arg("state"), "Goes on from a saved state of this scene.")
      .def("save_file", &Session::saveFile, nb::arg("path"), "save(), written to an HDF5 file.")
      .def("restore_file", &Session::restoreFile, nb::arg("path"), "restore() from a file save_file wrote.")
      .def("held_commands",
           [](const Session& s) {
             std::vector<double> v(s.model().inputs.size());
             for (std::size_t k = 0; k < v.size(); ++k) v[k] = s.model().inputs[k].signal->held();
             return vector(v.data(), v.size());
           },
           "Each input's command as held now.")
      .def_prop_ro("complete", [](const Session& s) { return s.outcome().complete; })
      .def_prop_ro("message", [](const Session& s) { return s.outcome().message; })
      .def("statistics",
           [](const Session& s) {
             const SolverStatistics st = s.outcome().statistics;
             nb::dict d;
             d["steps"] = st.steps;
             d["residual_evaluations"] = st.residual_evaluations;
             d["jacobian_evaluations"] = st.jacobian_evaluations;
             d["error_test_failures"] = st.error_test_failures;
             d["nonlinear_failures"] = st.nonlinear_failures;
             d["restarts"] = st.restarts;
             d["last_step_size"] = st.last_step_size;
             d["last_order"] = st.last_order;
             d["wall_time_s"] = st.wall_time_s;
             return d;
           },
           "The solver's counters and the wall time spent advancing.")
      .def("joint_position", [](const Session& s, int j) { return vector(s.jointPosition(j)); }, nb::arg("joint"))
      .def("joint_velocity", [](const Session& s, int j) { return vector(s.jointVelocity(j)); }, nb::arg("joint"))
      .def_prop_ro("joint_names", [](const Session& s) { return namesOf(s.model().joints); })
      .def_prop_ro("constraint_names", [](const Session& s) { return namesOf(s.model().constraints); })
      .def("constraint", &Session::constraint, nb::arg("name"), "The index of the constraint named `name`.")
      .def("constraint_load",
           [](const Session& s, int c) {
             const ConstraintReaction load = s.constraintLoad(c);
             const double values[] = {load.force.x(),  load.force.y(),  load.force.z(),
                                      load.moment.x(), load.moment.y(), load.moment.z()};
             return vector(values, 6);
           },
           nb::arg("constraint"), "[force (3), moment (3)] the constraint carries now, in its first joint's axes.")
      .def("rope_tensions",
           [](const Session& s, const std::string& rope) {
             const std::vector<double> t = s.ropeTensions(rope);
             return vector(t.data(), t.size());
           },
           nb::arg("rope"), "A rope's axial force along its elements (a reeved rope's parts) now, kTensionPoints per element.")
      .def("drive_power", &Session::drivePower, nb::arg("constraint"), "The power a constraint's drive delivers now, W.")
      .def("winch_power", &Session::winchPower, nb::arg("rope"), "The power a rope's winch delivers now, W.")
      .def("sway",
           [](const Session& s, int hanging, int pivot) {
             const Session::Sway w = s.sway(hanging, pivot);
             const double values[] = {w.radial, w.across, w.radial_rate, w.across_rate};
             return vector(values, 4);
           },
           nb::arg("hanging"), nb::arg("pivot"), "[radial, across, their rates] of the line from pivot to hanging.")
      .def("kinetic_energy", &Session::kineticEnergy)
      .def("potential_energy", &Session::potentialEnergy);

  nb::class_<SwayAxisController>(m, "SwayAxis", "Anti-sway LQR along one horizontal axis (cranesim.control.SwayAxis).")
      .def(
          "__init__",
          [](SwayAxisController* self, double sample_time, double drive_lag, double gravity, double position, double speed,
             double angle, double angle_rate, double command, double reschedule, double measurement_cutoff,
             double steady_angle_time) {
            new (self) SwayAxisController(SwayAxisSpec{sample_time, drive_lag, gravity, position, speed, angle, angle_rate,
                                                       command, reschedule, measurement_cutoff, steady_angle_time});
          },
          nb::arg("sample_time"), nb::arg("drive_lag"), nb::arg("gravity"), nb::arg("position"), nb::arg("speed"),
          nb::arg("angle"), nb::arg("angle_rate"), nb::arg("command"), nb::arg("reschedule"), nb::arg("measurement_cutoff"),
          nb::arg("steady_angle_time"))
      .def("command", &SwayAxisController::command, nb::arg("rope_length"), nb::arg("position_error"), nb::arg("speed"),
           nb::arg("reference_speed"), nb::arg("angle"), nb::arg("angle_rate"))
      .def_prop_ro(
          "gain", [](const SwayAxisController& c) { return vector(c.gain().data(), 4); }, nb::rv_policy::move)
      .def_prop_ro("design_length", &SwayAxisController::designLength)
      .def_prop_ro("closed_loop_spectral_radius",
                   [](const SwayAxisController& c) { return c.closedLoop().eigenvalues().cwiseAbs().maxCoeff(); });

  nb::class_<CraneSwayController>(m, "CraneSway", "Anti-sway feedback on a session (cranesim.control.AntiSway).")
      .def(
          "__init__",
          [](CraneSwayController* self, Session& session, const std::string& slewing, const std::string& luffing_rope,
             const std::string& hoist_rope, const std::string& hook, const std::string& sheave, const SwayAxisController& across,
             const SwayAxisController& along, double shaping_period, double boom_period, double angle_noise,
             double rate_noise, double delay, std::uint64_t seed) {
            nb::gil_scoped_release released;
            CraneSwaySpec spec{slewing, luffing_rope, hoist_rope, hook, sheave, across.spec(), along.spec()};
            spec.shaping_period = shaping_period;
            spec.boom_period = boom_period;
            spec.sensor = {angle_noise, rate_noise, delay, seed};
            new (self) CraneSwayController(session, spec);
          },
          nb::arg("session"), nb::arg("slewing"), nb::arg("luffing_rope"), nb::arg("hoist_rope"), nb::arg("hook"),
          nb::arg("sheave"), nb::arg("across"), nb::arg("along"), nb::arg("shaping_period") = 0.0,
          nb::arg("boom_period") = 0.0, nb::arg("angle_noise") = 0.0, nb::arg("rate_noise") = 0.0,
          nb::arg("delay") = 0.0, nb::arg("seed") = 0, nb::keep_alive<1, 2>())
      .def(
          "apply",
          [](CraneSwayController& c, double slewing, double luffing, double hoist) {
            const std::vector<double> held = c.apply(slewing, luffing, hoist);
            return vector(held.data(), held.size());
          },
          nb::arg("slewing"), nb::arg("luffing"), nb::arg("hoist"))
      .def("head_per_luff", &CraneSwayController::headPerLuff, nb::arg("length"));

  m.def("write_static",
        [](const std::string& path, const std::string& text, const std::string& name, const std::string& out) {
          return writeStatic(scene(path, text, name), out);
        },
        nb::arg("path"), nb::arg("text"), nb::arg("name"), nb::arg("out"),
        "The scene's static equilibrium written as `crane-sim static` writes it; why it is unstable, or ''.");
  m.def("write_modes",
        [](const std::string& path, const std::string& text, const std::string& name, int count, const std::string& out) {
          writeModesFile(scene(path, text, name), count, out);
        },
        nb::arg("path"), nb::arg("text"), nb::arg("name"), nb::arg("count"), nb::arg("out"),
        "The lowest `count` modes about the equilibrium written as `crane-sim modes` writes them.");
  m.def("run_study",
        [](const std::string& path, const std::string& out, int jobs, bool resume) {
          read(path, [&] { return readStudy(path); });
          const std::atomic<int> interrupt_signal{SIGINT};
          return read(path, [&] {
            return interruptibly([&](const std::atomic<bool>& stop) {
              return runStudyCommand({path, out, jobs, resume, true, &stop, &interrupt_signal});
            });
          });
        },
        nb::arg("path"), nb::arg("out"), nb::arg("jobs"), nb::arg("resume"),
        "`crane-sim study` on the study file at `path`; its exit code (0: every case computed).");
  m.attr("tension_points") = kTensionPoints;
}
