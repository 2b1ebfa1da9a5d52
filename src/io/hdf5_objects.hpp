// Internal to oscidrum_io: the HDF5 objects the writers share (identifiers closed on scope exit,
// quiet errors, attributes with units, 1-D datasets, dimension scales), over HDF5's C API.
#pragma once

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "oscidrum/error.hpp"

namespace oscidrum::io::h5 {

// HDF5 prints a stack of messages on every failed call unless told not to; errors here become
// oscidrum::Error instead. Restores the previous handler when it goes.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// An HDF5 identifier closed by `close` when it goes out of scope.
class Id {
 public:
  Id() = default;
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Id() { reset(); }
  Id(Id&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Id& operator=(Id&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      close_ = o.close_;
    }
    return *this;
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool ok() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw Error(what);
}

inline Id checked(hid_t id, herr_t (*close)(hid_t), const std::string& what) {
  if (id < 0) throw Error(what);
  return Id(id, close);
}

inline Id string_type() {
  Id t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

inline Id scalar_space() { return Id(H5Screate(H5S_SCALAR), H5Sclose); }

inline Id vector_space(std::size_t n) {
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  return Id(H5Screate_simple(1, dims, nullptr), H5Sclose);
}

inline void attr_string(hid_t obj, const char* name, const std::string& value,
                        const std::string& file) {
  const Id type = string_type();
  const Id space = scalar_space();
  const Id a = checked(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                       "cannot write " + file + ": attribute " + name);
  const char* p = value.c_str();
  check(H5Awrite(a, type, &p), "cannot write " + file + ": attribute " + name);
}

inline void attr_int(hid_t obj, const char* name, std::int64_t value, const std::string& file) {
  const Id space = scalar_space();
  const Id a = checked(H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                       H5Aclose, "cannot write " + file + ": attribute " + name);
  check(H5Awrite(a, H5T_NATIVE_INT64, &value), "cannot write " + file + ": attribute " + name);
}

inline void attr_double(hid_t obj, const char* name, double value, const std::string& file) {
  const Id space = scalar_space();
  const Id a = checked(H5Acreate2(obj, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                       H5Aclose, "cannot write " + file + ": attribute " + name);
  check(H5Awrite(a, H5T_NATIVE_DOUBLE, &value), "cannot write " + file + ": attribute " + name);
}

inline void attr_strings(hid_t obj, const char* name, const std::vector<std::string>& values,
                         const std::string& file) {
  const Id type = string_type();
  const Id space = vector_space(values.size());
  const Id a = checked(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                       "cannot write " + file + ": attribute " + name);
  std::vector<const char*> p;
  for (const std::string& v : values) p.push_back(v.c_str());
  if (!p.empty())
    check(H5Awrite(a, type, p.data()), "cannot write " + file + ": attribute " + name);
}

inline std::string read_attr_string(hid_t obj, const char* name, const std::string& file) {
  if (H5Aexists(obj, name) <= 0) throw Error(file + ": attribute " + name + " missing");
  const Id a = checked(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, file + ": attribute " + name);
  const Id type = string_type();
  char* p = nullptr;
  check(H5Aread(a, type, &p), file + ": attribute " + name + " is not a string");
  std::string s = p ? p : "";
  H5free_memory(p);
  return s;
}

inline std::int64_t read_attr_int(hid_t obj, const char* name, const std::string& file) {
  if (H5Aexists(obj, name) <= 0) throw Error(file + ": attribute " + name + " missing");
  const Id a = checked(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, file + ": attribute " + name);
  std::int64_t v = 0;
  check(H5Aread(a, H5T_NATIVE_INT64, &v), file + ": attribute " + name + " is not an integer");
  return v;
}

inline double read_attr_double(hid_t obj, const char* name, const std::string& file) {
  if (H5Aexists(obj, name) <= 0) throw Error(file + ": attribute " + name + " missing");
  const Id a = checked(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, file + ": attribute " + name);
  double v = 0;
  check(H5Aread(a, H5T_NATIVE_DOUBLE, &v), file + ": attribute " + name + " is not a number");
  return v;
}

// Elements per chunk of a compressed dataset (the steady states' columns).
inline constexpr std::size_t kChunk = 16384;
// The deflate level of the steady states. Level 1: the same size as level 4 on steady states
// (2000 of them: 369 MB against 368 MB; 647 MB uncompressed) in a third of the time.
inline constexpr int kDeflateLevel = 1;

// A 1-D dataset; `compress`: chunked, shuffled and deflated (the steady states).
inline Id create_dataset(hid_t group, const std::string& name, hid_t file_type, std::size_t n,
                         bool compress, const std::string& file) {
  const Id space = vector_space(n);
  Id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (compress && n > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    const hsize_t chunk[1] = {std::min<hsize_t>(n, kChunk)};
    H5Pset_chunk(plist, 1, chunk);
    H5Pset_shuffle(plist);
    H5Pset_deflate(plist, kDeflateLevel);
  }
  return checked(H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
                 H5Dclose, "cannot write " + file + ": dataset " + name);
}

inline void write_doubles(hid_t group, const std::string& name, const std::vector<double>& v,
                          const std::string& unit, bool compress, const std::string& file) {
  const Id d = create_dataset(group, name, H5T_IEEE_F64LE, v.size(), compress, file);
  if (!v.empty())
    check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot write " + file + ": dataset " + name);
  if (!unit.empty()) attr_string(d, "unit", unit, file);
}

inline void write_ints(hid_t group, const std::string& name, const std::vector<std::int64_t>& v,
                       hid_t file_type, bool compress, const std::string& file) {
  const Id d = create_dataset(group, name, file_type, v.size(), compress, file);
  if (!v.empty())
    check(H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot write " + file + ": dataset " + name);
}

inline void write_strings(hid_t group, const std::string& name, const std::vector<std::string>& v,
                          const std::string& file) {
  const Id type = string_type();
  const Id d = create_dataset(group, name, type, v.size(), false, file);
  std::vector<const char*> p;
  for (const std::string& s : v) p.push_back(s.c_str());
  if (!p.empty())
    check(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()),
          "cannot write " + file + ": dataset " + name);
}

// Make `scale` a dimension scale named `name` and attach it as dimension 0 of each of `datasets`
// (netCDF-4's dimensions: xarray opens the group with named dimensions and coordinates).
inline void attach_scale(hid_t scale, const char* name, const std::vector<hid_t>& datasets,
                         const std::string& file) {
  check(H5DSset_scale(scale, name), "cannot write " + file + ": dimension scale " + name);
  for (hid_t d : datasets)
    check(H5DSattach_scale(d, scale, 0), "cannot write " + file + ": dimension scale " + name);
}

}  // namespace oscidrum::io::h5
