// Pickling of the run's outputs (Result, Diagnostics, Samples, Metrics and a study's
// CaseOutcome): results travel between processes on executors (Dask, multiprocessing) and are
// cached with pickle. The state is a flat byte string of this build's structs, headed by a tag
// naming the type and the sizes of the fixed-size parts, so only the same oscidrum build reads it
// back. The members of Diagnostics, Samples and Metrics come from the output tables
// (oscidrum/outputs.hpp), so a new output travels without a change here.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/study.hpp"

namespace oscidrum::python::pickling {

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    bytes_ += s;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(std::string_view bytes, const char* type) : bytes_(bytes), type_(type) {}
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof(T));
  }
  template <class T>
  void get(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t n = 0;
    get(n);
    if (n > (bytes_.size() - pos_) / sizeof(T)) fail();
    v.resize(n);
    if (n > 0) take(v.data(), n * sizeof(T));
  }
  void get(std::string& s) {
    std::uint64_t n = 0;
    get(n);
    if (n > bytes_.size() - pos_) fail();
    s.assign(bytes_.substr(pos_, n));
    pos_ += n;
  }
  template <class T>
  T get() {
    T v{};
    get(v);
    return v;
  }
  bool at_end() const { return pos_ == bytes_.size(); }
  [[noreturn]] void fail() const {
    throw Error(std::string("cannot restore a ") + type_ +
                ": the state is not one written by this build of oscidrum");
  }

 private:
  void take(void* out, std::size_t n) {
    if (n > bytes_.size() - pos_) fail();
    std::memcpy(out, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::string_view bytes_;
  const char* type_;
  std::size_t pos_ = 0;
};

// Every member of each type, in one order for writing (Writer) and reading (Reader).
template <class IO>
void members(IO&& io, Diagnostics& d) {
#define OSCIDRUM_MEMBER(type, name, initial, unit, label, description) io(d.name);
  OSCIDRUM_DIAGNOSTICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
}

template <class IO>
void members(IO&& io, Samples& s) {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) io(s.name);
  OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
}

template <class IO>
void members(IO&& io, Metrics& m) {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) io(m.name);
  OSCIDRUM_METRICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
}

template <class IO>
void members(IO&& io, Result& r) {
  io(r.status), io(r.message);
  members(io, r.diagnostics);
  io(r.frequency), io(r.sample_periods), io(r.samples_per_period);
  members(io, r.samples);
  io(r.events), io(r.stick_time), io(r.slip_positive_time), io(r.slip_negative_time),
      io(r.flight_time);
  io(r.floquet.multipliers), io(r.floquet.max_modulus), io(r.floquet.stability);
  io(r.period1_floquet.multipliers), io(r.period1_floquet.max_modulus),
      io(r.period1_floquet.stability);
}

template <class IO>
void members(IO&& io, CaseOutcome& o) {
  io(o.valid), io(o.error);
  members(io, o.result);
  members(io, o.metrics);
}

// The tag heading each type's state: "OSR1", "OSD1", ...
template <class T>
constexpr std::uint32_t tag();
template <>
constexpr std::uint32_t tag<CaseOutcome>() {
  return 0x4f534334;  // "OSC4"
}
template <>
constexpr std::uint32_t tag<Result>() {
  return 0x4f535231;  // "OSR1"
}
template <>
constexpr std::uint32_t tag<Diagnostics>() {
  return 0x4f534431;  // "OSD1"
}
template <>
constexpr std::uint32_t tag<Samples>() {
  return 0x4f535331;  // "OSS1"
}
template <>
constexpr std::uint32_t tag<Metrics>() {
  return 0x4f534d31;  // "OSM1"
}

template <class T>
py::bytes state(const T& value) {
  Writer w;
  w.put(tag<T>());
  w.put<std::uint32_t>(sizeof(Event));
  w.put<std::uint32_t>(sizeof(Harmonic));
  // members() takes a mutable reference for the Reader's sake; the Writer only reads.
  members([&](const auto& v) { w.put(v); }, const_cast<T&>(value));
  return py::bytes(w.bytes());
}

template <class T>
T from_state(py::handle state, const char* type) {
  if (!py::isinstance<py::bytes>(state))
    throw Error(std::string("cannot restore a ") + type + " from " + python_description(state) +
                "; expected the bytes of its __getstate__");
  const std::string bytes = state.cast<std::string>();
  Reader rd(bytes, type);
  if (rd.get<std::uint32_t>() != tag<T>() || rd.get<std::uint32_t>() != sizeof(Event) ||
      rd.get<std::uint32_t>() != sizeof(Harmonic))
    rd.fail();
  T value;
  members([&](auto& v) { rd.get(v); }, value);
  if (!rd.at_end()) rd.fail();
  return value;
}

/// __getstate__ and __setstate__ for a class built on __new__ (construct_on_new): pickle makes
/// the default value, and __setstate__ assigns the state to it.
template <class T>
void def_pickle(py::class_<T>& cls, const char* type) {
  cls.def("__getstate__", [](const T& value) { return state(value); });
  def_assigning(cls, "__setstate__",
                [type](T& self, py::handle s) { self = from_state<T>(s, type); });
}

}  // namespace oscidrum::python::pickling
