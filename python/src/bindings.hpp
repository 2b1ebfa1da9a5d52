// python/src/bindings.hpp: the pieces of the oscidrum._core extension module. One bind_*
// function per public header of the library.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <future>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/parameters.hpp"

namespace oscidrum::python {

namespace py = pybind11;

/// An integer argument that refuses True and False: pybind11 takes a bool for an int (Python's
/// bool is an int), so harmonics(y, True, f) ran over one cycle and synthetic_record(seed=True)
/// used seed 1 without a word. Converts to T where the function uses it.
template <class T>
struct Strict {
  T value{};
  operator T() const { return value; }  // NOLINT(google-explicit-constructor): used as a T
};
using Int = Strict<int>;
using UInt = Strict<unsigned>;

}  // namespace oscidrum::python

namespace pybind11::detail {
template <class T>
struct type_caster<oscidrum::python::Strict<T>> {
  PYBIND11_TYPE_CASTER(oscidrum::python::Strict<T>, make_caster<T>::name);
  bool load(handle src, bool convert) {
    if (PyBool_Check(src.ptr())) return false;
    make_caster<T> inner;
    if (!inner.load(src, convert)) return false;
    value.value = cast_op<T>(inner);
    return true;
  }
  static handle cast(const oscidrum::python::Strict<T>& v, return_value_policy p, handle parent) {
    return make_caster<T>::cast(v.value, p, parent);
  }
};
}  // namespace pybind11::detail

namespace oscidrum::python {

void bind_error(py::module_& m);
void bind_fields(py::module_& m);
void bind_parameters(py::module_& m);
void bind_state(py::module_& m);
void bind_kinematics(py::module_& m);
void bind_model(py::module_& m);
void bind_result(py::module_& m);
void bind_simulate(py::module_& m);
void bind_metrics(py::module_& m);
void bind_study(py::module_& m);
void bind_soil(py::module_& m);
void bind_transmissibility(py::module_& m);
void bind_record(py::module_& m);
void bind_identify(py::module_& m);
void bind_validation(py::module_& m);
void bind_branch(py::module_& m);
void bind_diagram(py::module_& m);
void bind_files(py::module_& m);

/// How often a long computation looks for Ctrl-C (PyErr_CheckSignals): 50 ms in steady_clock
/// ticks, so that worker threads do not queue for the GIL.
inline constexpr std::int64_t kPollTicks =
    std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(50))
        .count();

/// A NumPy array holding a copy of `v`.
inline py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// Python callbacks and Ctrl-C for a computation that runs with the GIL released (a study, the
/// paper's studies, a branch), from any of its threads: guarded(call) runs `call` with the GIL
/// and keeps the first exception it raises; cancelled() is true once there is one or Ctrl-C was
/// seen (looked for at most every kPollTicks); rethrow() raises the kept exception once the GIL
/// is back.
class GuardedCalls {
 public:
  template <class F>
  void guarded(F&& call) {
    py::gil_scoped_acquire gil;
    if (error_) return;
    try {
      call();
    } catch (...) {
      error_ = std::current_exception();  // written with the GIL held: the GIL guards it
      stop_.store(true);
    }
  }
  bool cancelled() {
    if (stop_.load()) return true;
    const std::int64_t now = std::chrono::steady_clock::now().time_since_epoch().count();
    std::int64_t due = next_poll_.load();
    if (now < due || !next_poll_.compare_exchange_strong(due, now + kPollTicks)) return false;
    guarded([] {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    });
    return stop_.load();
  }
  /// Ctrl-C now (PyErr_CheckSignals, which acts only in the main thread).
  void check_signals() {
    guarded([] {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    });
  }
  bool failed() const { return static_cast<bool>(error_); }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::exception_ptr error_;
  std::atomic<bool> stop_{false};           // set once error_ is: read without the GIL
  std::atomic<std::int64_t> next_poll_{0};  // steady_clock ticks of the next signal check
};

/// Runs `work` with the GIL released on a thread of its own while the calling thread looks for
/// Ctrl-C every 50 ms (calls.check_signals). Python handles signals only in its main thread: a
/// computation whose cases all run on worker threads (a study on two or more threads) polled
/// from those threads only, and a Ctrl-C waited for the whole study. Returns what `work`
/// returns, or throws what it threw.
template <class F>
std::invoke_result_t<F&> run_watching_signals(GuardedCalls& calls, F&& work) {
  using T = std::invoke_result_t<F&>;
  std::promise<T> promise;
  std::future<T> future = promise.get_future();
  py::gil_scoped_release release;
  std::thread worker([&] {
    try {
      if constexpr (std::is_void_v<T>) {
        work();
        promise.set_value();
      } else {
        promise.set_value(work());
      }
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  });
  while (future.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready)
    calls.check_signals();
  worker.join();
  return future.get();
}

/// The field key a Python name stands for: the dotted key itself, or the field of a flat alias
/// ("mu" -> "contact.mu"); any other name unchanged (the library names what it refuses).
std::string dotted_field_key(std::string_view name);

/// A float64 NumPy array argument (converted if needed, C-contiguous).
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The data of a 1-D array as a span; oscidrum::Error naming the argument if it is not 1-D.
std::span<const double> span_of(const Array& a, const char* name);

/// The name of a Python value's type ("int", "list", ...), for messages.
std::string python_type_name(py::handle value);

/// A Python value for a message: its type and its repr, cut after 60 characters ("int (5)").
std::string python_description(py::handle value);

/// The value of a field as a Python object: float (real), int (integer), bool (boolean) or str
/// (choice name).
py::object field_value(const Case& c, const Field& field);

/// Set a field from a Python value (number, bool, or text as set_field_text reads it). Throws
/// oscidrum::Error with the library's message when the value breaks the field's rule.
void set_field_value(Case& c, std::string_view key, py::handle value);

/// A Python value for the field `key` judged as assigning it to a Case judges it (its type: no
/// True for a number, no 2.0 for an integer; its rule, with the library's message and hints):
/// the value, or oscidrum::Error. For arguments that stand for a field (soil_coefficients' G).
double field_argument(std::string_view key, py::handle value);

/// Make `T.__new__(T)` (without __init__) give a default-constructed T instead of uninitialised
/// memory: the type's tp_new constructs the value and its holder. The class must then define
/// __init__ (and __setstate__) as ordinary methods that assign to the already-built value, since
/// pybind11 ignores a constructor on an instance that is already built.
template <class T>
void construct_on_new(py::class_<T> cls) {
  cls.def_static("__new__", [](py::handle subtype, const py::args&, const py::kwargs&) {
    auto* type = reinterpret_cast<PyTypeObject*>(subtype.ptr());
    PyObject* self = py::detail::pybind11_object_new(type, nullptr, nullptr);
    if (self == nullptr) throw py::error_already_set();
    auto* inst = reinterpret_cast<py::detail::instance*>(self);
    auto v_h = inst->get_value_and_holder(py::detail::get_type_info(typeid(T)));
    v_h.value_ptr() = new T();
    v_h.type->init_instance(inst, nullptr);
    return py::reinterpret_steal<py::object>(self);
  });
}

/// Define `attr` (__init__ or __setstate__) as an ordinary method on a class made by
/// construct_on_new: pybind11 treats functions *named* __init__/__setstate__ as constructors and
/// skips them on an instance that is already built, so the function gets another name.
template <class Cls, class F, class... Extra>
void def_assigning(Cls& cls, const char* attr, F&& f, const Extra&... extra) {
  cls.attr(attr) =
      py::cpp_function(std::forward<F>(f), py::name(attr[2] == 'i' ? "_init" : "_setstate"),
                       py::is_method(cls), extra...);
}

/// Make an enum's constructor strict: Status(99), Status(True) or Status(2.0) raise
/// oscidrum.Error instead of making a value outside the enumeration; the member's name is
/// accepted too (Status('chattering')).
template <class E>
void strict_enum(py::enum_<E>& e) {
  py::handle type = e;
  e.def(py::init([type](py::handle value) {
          const py::dict members = type.attr("__members__");
          if (py::isinstance<E>(value)) return value.cast<E>();
          const std::string name = py::str(type.attr("__name__"));
          std::string names;
          for (auto item : members) {
            const long long number =
                py::int_(py::reinterpret_borrow<py::object>(item.second)).cast<long long>();
            names += (names.empty() ? "" : ", ") + py::str(item.first).cast<std::string>() + " (" +
                     std::to_string(number) + ")";
            if (py::isinstance<py::str>(value) && py::str(item.first).equal(value))
              return item.second.cast<E>();
            if (PyLong_Check(value.ptr()) && !py::isinstance<py::bool_>(value)) {
              int overflow = 0;
              const long long i = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
              if (overflow == 0 && i == number) return item.second.cast<E>();
            }
          }
          throw Error(name + " must be one of " + names + "; got " +
                      py::repr(value).cast<std::string>());
        }),
        py::arg("value"), py::prepend());
}

}  // namespace oscidrum::python
