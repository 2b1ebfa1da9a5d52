// A study in one HDF5 file (HDF5's C API), and the merge of shard files. Layout: docs/outputs.md.
#include "oscidrum_io/hdf5.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <span>
#include <utility>

#include "hdf5_objects.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"

namespace oscidrum::io {
namespace {

using namespace h5;  // NOLINT: the helpers of hdf5_objects.hpp

constexpr const char* kFormat = "oscidrum-study";
constexpr std::int64_t kFormatVersion = 1;

// The chunks of one column as HDF5's filters would store them: each chunk of kChunk elements
// (the last one padded with zeros to a whole chunk, as HDF5 fills it) byte-shuffled (byte k of
// every element together, the shuffle filter) and deflated into a zlib stream (the deflate
// filter, compress2 at kDeflateLevel). Thread-safe: no HDF5 call.
template <class T>
std::vector<std::vector<unsigned char>> filtered_chunks(const std::vector<T>& v) {
  std::vector<std::vector<unsigned char>> out;
  const std::size_t n = v.size(), chunk = std::min(n, kChunk);
  if (n == 0) return out;
  std::vector<unsigned char> shuffled(chunk * sizeof(T));
  for (std::size_t first = 0; first < n; first += chunk) {
    std::fill(shuffled.begin(), shuffled.end(), 0);
    const std::size_t count = std::min(chunk, n - first);
    const auto* bytes = reinterpret_cast<const unsigned char*>(v.data() + first);
    for (std::size_t e = 0; e < count; ++e)
      for (std::size_t b = 0; b < sizeof(T); ++b)
        shuffled[b * chunk + e] = bytes[e * sizeof(T) + b];
    uLongf size = compressBound(static_cast<uLong>(shuffled.size()));
    std::vector<unsigned char> packed(size);
    if (compress2(packed.data(), &size, shuffled.data(), static_cast<uLong>(shuffled.size()),
                  kDeflateLevel) != Z_OK)
      throw Error("cannot compress a steady state for the HDF5 file (zlib)");
    packed.resize(size);
    out.push_back(std::move(packed));
  }
  return out;
}

// Write the prepared chunks of a dataset made by create_dataset(..., compress = true).
void write_chunks(hid_t d, std::size_t n, const std::vector<std::vector<unsigned char>>& chunks,
                  const std::string& what) {
  const std::size_t chunk = std::min(n, kChunk);
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    const hsize_t offset[1] = {static_cast<hsize_t>(k * chunk)};
    check(H5Dwrite_chunk(d, H5P_DEFAULT, 0, offset, chunks[k].size(), chunks[k].data()), what);
  }
}

// The same as attach_scale for a scale that is attached once to every dataset of a new group, in
// four attribute writes instead of H5DSattach_scale's read-modify-write of the scale's list per
// dataset (which cost about 1 ms per steady state of a sweep, a quarter of its --hdf5 time):
// the attributes of the HDF5 dimension scale specification as H5DS writes them (CLASS and NAME
// on the scale; REFERENCE_LIST on it, a {dataset, dimension} compound per attached dataset;
// DIMENSION_LIST on each dataset, one variable-length list of references per dimension).
void attach_scale_at_once(hid_t scale, const char* name, const std::vector<hid_t>& datasets,
                          const std::string& file) {
  const std::string what = "cannot write " + file + ": dimension scale " + name;
  auto fixed_string = [&](const char* key, const char* text) {
    const Id type(H5Tcopy(H5T_C_S1), H5Tclose);
    check(H5Tset_size(type, std::strlen(text) + 1), what);
    check(H5Tset_strpad(type, H5T_STR_NULLTERM), what);
    const Id space(H5Screate(H5S_SCALAR), H5Sclose);
    const Id a =
        checked(H5Acreate2(scale, key, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, what);
    check(H5Awrite(a, type, text), what);
  };
  fixed_string("CLASS", "DIMENSION_SCALE");
  fixed_string("NAME", name);
  hobj_ref_t scale_ref;
  check(H5Rcreate(&scale_ref, scale, ".", H5R_OBJECT, -1), what);
  struct Entry {
    hobj_ref_t dataset;
    int dimension;
  };
  std::vector<Entry> entries;
  const Id vlen(H5Tvlen_create(H5T_STD_REF_OBJ), H5Tclose);
  const hsize_t one[1] = {1};
  const Id one_space(H5Screate_simple(1, one, nullptr), H5Sclose);
  for (hid_t d : datasets) {
    Entry e{};
    check(H5Rcreate(&e.dataset, d, ".", H5R_OBJECT, -1), what);
    e.dimension = 0;
    entries.push_back(e);
    hvl_t list{1, &scale_ref};
    const Id a = checked(H5Acreate2(d, "DIMENSION_LIST", vlen, one_space, H5P_DEFAULT, H5P_DEFAULT),
                         H5Aclose, what);
    check(H5Awrite(a, vlen, &list), what);
  }
  const Id entry(H5Tcreate(H5T_COMPOUND, sizeof(Entry)), H5Tclose);
  check(H5Tinsert(entry, "dataset", HOFFSET(Entry, dataset), H5T_STD_REF_OBJ), what);
  check(H5Tinsert(entry, "dimension", HOFFSET(Entry, dimension), H5T_NATIVE_INT), what);
  const hsize_t n[1] = {entries.size()};
  const Id space(H5Screate_simple(1, n, nullptr), H5Sclose);
  const Id a = checked(H5Acreate2(scale, "REFERENCE_LIST", entry, space, H5P_DEFAULT, H5P_DEFAULT),
                       H5Aclose, what);
  check(H5Awrite(a, entry, entries.data()), what);
}

std::size_t dataset_size(hid_t d) {
  const Id space(H5Dget_space(d), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  return n < 0 ? 0 : static_cast<std::size_t>(n);
}

std::vector<double> read_doubles(hid_t d, const std::string& what) {
  std::vector<double> v(dataset_size(d));
  if (!v.empty())
    check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), what);
  return v;
}

std::vector<std::int64_t> read_ints(hid_t d, const std::string& what) {
  std::vector<std::int64_t> v(dataset_size(d));
  if (!v.empty())
    check(H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), what);
  return v;
}

std::vector<std::string> read_strings(hid_t d, const std::string& what) {
  const std::size_t n = dataset_size(d);
  std::vector<std::string> out;
  if (n == 0) return out;
  const Id type = string_type();
  std::vector<char*> p(n, nullptr);
  check(H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), what);
  for (char* s : p) {
    out.emplace_back(s ? s : "");
    H5free_memory(s);
  }
  return out;
}

// Copy every attribute of `src` to `dst` (same types and values).
void copy_attributes(hid_t src, hid_t dst, const std::string& file) {
  H5O_info_t info;
  check(H5Oget_info(src, &info), "cannot read " + file);
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    const Id a(
        H5Aopen_by_idx(src, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    const Id a2 =
        a.ok()
            ? Id()
            : Id(H5Aopen_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
    const hid_t attr = a.ok() ? a.get() : a2.get();
    if (attr < 0) throw Error("cannot read " + file + ": an attribute");
    char name[256];
    H5Aget_name(attr, sizeof name, name);
    if (H5Aexists(dst, name) > 0) continue;
    // A dimension scale's attributes hold references into their own file: the copy attaches
    // its scales anew.
    if (std::strcmp(name, "CLASS") == 0 || std::strcmp(name, "NAME") == 0 ||
        std::strcmp(name, "REFERENCE_LIST") == 0 || std::strcmp(name, "DIMENSION_LIST") == 0)
      continue;
    const Id type(H5Aget_type(attr), H5Tclose);
    const Id space(H5Aget_space(attr), H5Sclose);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<unsigned char> buf(static_cast<std::size_t>(std::max<hssize_t>(n, 1)) *
                                   H5Tget_size(type));
    check(H5Aread(attr, type, buf.data()), "cannot read " + file + ": attribute " + name);
    const Id out = checked(H5Acreate2(dst, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                           "cannot write attribute " + std::string(name));
    check(H5Awrite(out, type, buf.data()), "cannot write attribute " + std::string(name));
    if (H5Tis_variable_str(type) > 0 || H5Tdetect_class(type, H5T_VLEN) > 0)
      H5Dvlen_reclaim(type, space, H5P_DEFAULT, buf.data());
  }
}

// The names of the links in a group, in name order.
std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info;
  std::vector<std::string> names;
  if (H5Gget_info(group, &info) < 0) return names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) continue;
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(name);
  }
  return names;
}

std::string case_group(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06zu", index);
  return buf;
}

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

// "ddx_max[m/s^2]" -> ("ddx_max", "m/s^2"); a swept key's label may be quoted in the CSV.
std::pair<std::string, std::string> split_label(const std::string& label) {
  const std::size_t open = label.rfind('[');
  if (open == std::string::npos || label.back() != ']') return {label, "-"};
  return {label.substr(0, open), label.substr(open + 1, label.size() - open - 2)};
}

// The steady-state columns of docs/csv-columns.md, from the output table: every numeric column
// (the phase, an enumeration, is written apart as int8).
struct SampleColumn {
  const char* name;
  const char* unit;
  const std::vector<double> Samples::*values;
};
std::vector<SampleColumn> sample_columns() {
  std::vector<SampleColumn> out;
  for (const SampleOutput& o : sample_outputs())
    if (const auto* m = std::get_if<SampleValues Samples::*>(&o.member))
      out.push_back({o.name, o.unit, *m});
  return out;
}

// A case's steady state as netCDF-4 dimensions: its column t the dimension scale "t" of every
// column (xarray opens the group with the dimension t and t as its coordinate). A group copied
// from another file (merge) first loses the copied scale attributes, whose references point into
// that file; it may lack a column added since its file was written (alpha, the excitation's angle:
// a shard of an older oscidrum), which the merged file then lacks for that case too.
void attach_time_scale(hid_t group, const std::string& file, bool copied) {
  std::vector<std::string> names;
  for (const SampleColumn& c : sample_columns()) names.emplace_back(c.name);
  names.emplace_back("phase");
  if (copied)
    std::erase_if(names, [&](const std::string& name) {
      return name == "alpha" && H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0;
    });
  std::vector<Id> open;
  for (const std::string& name : names) {
    open.emplace_back(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!open.back().ok()) throw Error("cannot write " + file + ": no steady-state column " + name);
    if (copied)
      for (const char* a : {"DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME"})
        if (H5Aexists(open.back(), a) > 0) H5Adelete(open.back(), a);
  }
  std::vector<hid_t> columns;
  hid_t t = -1;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == "t")
      t = open[k];
    else
      columns.push_back(open[k]);
  }
  if (t < 0) throw Error("cannot write " + file + ": no steady-state column t");
  attach_scale_at_once(t, "t", columns, file);
}

void write_root_attributes(hid_t file, const Hdf5StudyInfo& info, const std::string& path) {
  attr_string(file, "format", kFormat, path);
  attr_int(file, "format_version", kFormatVersion, path);
  attr_string(file, "oscidrum_version", oscidrum::version, path);
  attr_string(file, "study_fingerprint", hex(info.fingerprint), path);
  attr_int(file, "n_cases_in_study", static_cast<std::int64_t>(info.n_cases), path);
  attr_string(file, "shard", info.sharded ? info.shard.text() : std::string(), path);
}

bool signature(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  in.read(head, sizeof head);
  return in.gcount() == 8 && std::memcmp(head, "\x89HDF\r\n\x1a\n", 8) == 0;
}

// A new study file at `path` (named `file` in messages): the root's attributes and the empty
// group /steady_state, flushed.
Id create_study_file(const std::string& path, const Hdf5StudyInfo& info, const std::string& file) {
  Id f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) throw Error("cannot write " + file);
  write_root_attributes(f, info, file);
  const Id g = checked(H5Gcreate2(f, "steady_state", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       H5Gclose, "cannot write " + file);
  std::vector<std::string> order;  // the column order of docs/csv-columns.md
  for (const SampleColumn& c : sample_columns()) order.emplace_back(c.name);
  order.emplace_back("phase");
  attr_strings(g, "columns", order, file);
  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot write " + file);
  return f;
}

// The names of the links in `group` as far as they can be listed: false if the listing stopped
// short (a damaged group), with the names found before.
herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->emplace_back(name);
  return 0;
}
bool list_names(hid_t group, std::vector<std::string>& names) {
  hsize_t at = 0;
  return H5Literate(group, H5_INDEX_NAME, H5_ITER_NATIVE, &at, collect_name, &names) >= 0;
}

// True if the group `name` of `steady` (/steady_state of an interrupted sweep's partial file) is
// case `index`'s and reads back whole: its attributes, and every steady-state column read to its
// end (each chunk inflated: a chunk torn or never written fails zlib's check), all of one length.
bool case_reads_back(hid_t steady, const std::string& name, std::size_t index) {
  const Id g(H5Gopen2(steady, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.ok()) return false;
  try {
    if (read_attr_int(g, "case", name) != static_cast<std::int64_t>(index)) return false;
    (void)read_attr_string(g, "status", name);
    (void)read_attr_int(g, "sample_periods", name);
    (void)read_attr_int(g, "samples_per_period", name);
    (void)read_attr_double(g, "frequency", name);
  } catch (const Error&) {
    return false;
  }
  std::vector<std::string> columns;
  for (const SampleColumn& c : sample_columns()) columns.emplace_back(c.name);
  columns.emplace_back("phase");
  hssize_t n = -1;
  std::vector<double> values;
  for (const std::string& column : columns) {
    const Id d(H5Dopen2(g, column.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.ok()) return false;
    const Id space(H5Dget_space(d), H5Sclose);
    const hssize_t m = space.ok() ? H5Sget_simple_extent_npoints(space) : -1;
    if (m < 0 || (n >= 0 && m != n)) return false;
    n = m;
    values.resize(static_cast<std::size_t>(m));
    if (m > 0 && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      return false;
  }
  return true;
}

// Copy into the new study file `dst` (named `file` in messages) every case group of `src`, an
// interrupted sweep's partial file, that reads back whole (case_reads_back); its time scale is
// attached anew, as in a merge. False if any group was left out or the list of groups could not
// be read to its end.
bool copy_whole_cases(hid_t src, hid_t dst, std::size_t n_cases, const std::string& file) {
  const Id from(H5Gopen2(src, "steady_state", H5P_DEFAULT), H5Gclose);
  if (!from.ok()) return false;
  std::vector<std::string> names;
  bool whole = list_names(from, names);
  for (const std::string& name : names) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), index);
    if (ec != std::errc() || end != name.data() + name.size() || index >= n_cases ||
        name != case_group(index) || !case_reads_back(from, name, index)) {
      whole = false;
      continue;
    }
    const std::string full = "steady_state/" + name;
    bool copied = H5Ocopy(from, name.c_str(), dst, full.c_str(), H5P_DEFAULT, H5P_DEFAULT) >= 0;
    try {
      if (copied) {
        const Id g = checked(H5Gopen2(dst, full.c_str(), H5P_DEFAULT), H5Gclose, "");
        attach_time_scale(g, file, true);
      }
    } catch (const Error&) {
      copied = false;
    }
    if (!copied) {
      whole = false;
      if (H5Lexists(dst, full.c_str(), H5P_DEFAULT) > 0) H5Ldelete(dst, full.c_str(), H5P_DEFAULT);
    }
  }
  return whole;
}

}  // namespace

bool is_hdf5_file(const std::string& path) { return signature(path); }

struct StudyHdf5Writer::Impl {
  std::string path, partial;
  Id file;
  std::chrono::steady_clock::time_point flushed = std::chrono::steady_clock::now();
  bool damaged = false;  // the partial file resumed was (cases left out)

  void resume(const Hdf5StudyInfo& info);
};

// --resume: a kill between two flushes leaves a partial file whose last metadata (the B-tree of
// /steady_state, object headers) never reached the disk, while its root attributes still read:
// appending to it aborted inside libhdf5 (H5Gcreate2), or failed with HDF5's internals on stderr.
// So nothing is appended to it: a fresh partial file gets every case group of the old one that
// reads back whole (the journal's other cases run again, their groups missing), and replaces it
// (renamed over it, so that a kill meanwhile leaves the old one). A file that does not open, or
// whose attributes do not read, keeps no case; one of another study is refused.
void StudyHdf5Writer::Impl::resume(const Hdf5StudyInfo& info) {
  Id old(H5Fopen(partial.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (old.ok()) {
    std::string fingerprint, shard;
    try {
      fingerprint = read_attr_string(old, "study_fingerprint", partial);
      shard = read_attr_string(old, "shard", partial);
    } catch (const Error&) {
      old.reset();
    }
    if (old.ok() && (fingerprint != hex(info.fingerprint) ||
                     shard != (info.sharded ? info.shard.text() : std::string())))
      throw Error("the HDF5 file " + partial +
                  " belongs to a different study; run with --restart to discard it");
  }
  damaged = !old.ok();
  OutputFile fresh(partial, true);
  {
    const Id f = create_study_file(fresh.write_path(), info, partial);
    if (old.ok()) damaged = !copy_whole_cases(old, f, info.n_cases, partial);
    check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot write " + partial);
  }
  old.reset();
  fresh.commit();
  file = Id(H5Fopen(partial.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw Error("cannot write " + partial);
}

StudyHdf5Writer::StudyHdf5Writer(std::string path, const Hdf5StudyInfo& info, bool resume)
    : impl_(std::make_unique<Impl>()) {
  // Also while a damaged partial file is read: its errors are dealt with, never printed.
  const QuietErrors quiet;
  impl_->path = std::move(path);
  // Beside the file the name leads to (through symbolic links); a FIFO or device is refused: an
  // HDF5 file is written in place, with seeks.
  impl_->partial = output_target(impl_->path, true).path + ".partial";
  const std::string& partial = impl_->partial;
  (void)output_target(partial, true);
  std::error_code ec;
  if (resume && std::filesystem::exists(partial, ec)) {
    impl_->resume(info);
    return;
  }
  impl_->file = create_study_file(partial, info, partial);
}

StudyHdf5Writer::~StudyHdf5Writer() = default;

bool StudyHdf5Writer::partial_was_damaged() const { return impl_->damaged; }

bool StudyHdf5Writer::has_case(std::size_t index) const {
  const QuietErrors quiet;
  const std::string name = "steady_state/" + case_group(index);
  return H5Lexists(impl_->file, name.c_str(), H5P_DEFAULT) > 0;
}

StudyHdf5Writer::PreparedCase StudyHdf5Writer::prepare(const CaseOutcome& outcome) {
  // The file's types are little-endian IEEE doubles and int8: the bytes in memory, on the
  // machines oscidrum builds for (checked here, not assumed).
  static_assert(std::endian::native == std::endian::little, "the HDF5 chunks assume little-endian");
  PreparedCase p;
  const Samples& s = outcome.result.samples;
  for (const SampleColumn& c : sample_columns()) p.chunks.push_back(filtered_chunks(s.*(c.values)));
  std::vector<std::int8_t> phase;
  phase.reserve(s.phase.size());
  for (Phase ph : s.phase) phase.push_back(static_cast<std::int8_t>(static_cast<int>(ph)));
  p.chunks.push_back(filtered_chunks(phase));
  return p;
}

void StudyHdf5Writer::add_case(std::size_t index, const CaseOutcome& outcome) {
  add_case(index, outcome, prepare(outcome));
}

void StudyHdf5Writer::add_case(std::size_t index, const CaseOutcome& outcome,
                               const PreparedCase& prepared) {
  const QuietErrors quiet;
  const std::string& file = impl_->partial;
  const std::string name = "steady_state/" + case_group(index);
  if (H5Lexists(impl_->file, name.c_str(), H5P_DEFAULT) > 0)
    H5Ldelete(impl_->file, name.c_str(), H5P_DEFAULT);  // a rerun of a case
  const Id g = checked(H5Gcreate2(impl_->file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       H5Gclose, "cannot write " + file + ": group " + name);
  const Result& r = outcome.result;
  attr_int(g, "case", static_cast<std::int64_t>(index), file);
  attr_string(g, "status", outcome.valid ? to_string(r.status) : "invalid", file);
  attr_double(g, "frequency", r.frequency, file);
  attr_int(g, "sample_periods", r.sample_periods, file);
  attr_int(g, "samples_per_period", r.samples_per_period, file);
  const std::size_t n = r.samples.size();
  // The prepared chunks go in as they are (HDF5 would shuffle and deflate the same way); without
  // the deflate filter in this HDF5 library the columns are written plainly.
  const bool chunked = n > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0;
  const std::vector<SampleColumn> columns = sample_columns();
  if (prepared.chunks.size() != columns.size() + 1)
    throw Error("cannot write " + file + ": a prepared case with the wrong number of columns");
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const SampleColumn& c = columns[k];
    if (!chunked) {
      write_doubles(g, c.name, r.samples.*(c.values), c.unit, true, file);
      continue;
    }
    const Id d = create_dataset(g, c.name, H5T_IEEE_F64LE, n, true, file);
    write_chunks(d, n, prepared.chunks[k], "cannot write " + file + ": dataset " + c.name);
    if (*c.unit != '\0') attr_string(d, "unit", c.unit, file);
  }
  if (chunked) {
    const Id d = create_dataset(g, "phase", H5T_STD_I8LE, n, true, file);
    write_chunks(d, n, prepared.chunks.back(), "cannot write " + file + ": dataset phase");
  } else {
    std::vector<std::int64_t> phase;
    for (Phase p : r.samples.phase) phase.push_back(static_cast<int>(p));
    write_ints(g, "phase", phase, H5T_STD_I8LE, true, file);
  }
  {
    const Id d(H5Dopen2(g, "phase", H5P_DEFAULT), H5Dclose);
    attr_string(d, "unit", "-", file);
    attr_string(d, "meaning", "-1 slip-, 0 stick, 1 slip+, 2 flight", file);
  }
  attach_time_scale(g, file, false);
  // A kill after a flush keeps the cases before it for --resume (a case the journal has but the
  // file lacks is run again). Flushing after every case cost more than the cases; once a second
  // loses at most a second of work.
  const auto now = std::chrono::steady_clock::now();
  if (now - impl_->flushed >= std::chrono::seconds(1)) {
    H5Fflush(impl_->file, H5F_SCOPE_GLOBAL);
    impl_->flushed = now;
  }
}

void StudyHdf5Writer::finish(const Study& study, const std::vector<std::size_t>& indices,
                             const std::string& header, const std::vector<std::string>& rows) {
  if (rows.size() != indices.size())
    throw Error("cannot write " + impl_->path + ": " + std::to_string(rows.size()) +
                " result rows for " + std::to_string(indices.size()) + " cases");
  finish(study, indices, header, [&](std::size_t k) { return rows[k]; });
}

namespace {

// Rows per block of the tables: their memory is bounded by this, not by the number of cases.
constexpr std::size_t kBlockRows = 4096;

// Write `count` values of memory type `type` from `data` at [offset, offset + count) of `d`.
void write_block(hid_t d, hid_t type, std::size_t offset, std::size_t count, const void* data,
                 const std::string& what) {
  if (count == 0) return;
  const Id file_space(H5Dget_space(d), H5Sclose);
  const hsize_t start[1] = {offset};
  const hsize_t n[1] = {count};
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, n, nullptr), what);
  const Id memory_space = vector_space(count);
  check(H5Dwrite(d, type, memory_space, file_space, H5P_DEFAULT, data), what);
}

}  // namespace

void StudyHdf5Writer::finish(const Study& study, const std::vector<std::size_t>& indices,
                             const std::string& header,
                             const std::function<std::string(std::size_t)>& row) {
  const QuietErrors quiet;
  const std::string& file = impl_->partial;
  const std::size_t n = indices.size();
  std::vector<std::int64_t> cases(indices.begin(), indices.end());
  write_ints(impl_->file, "case", cases, H5T_STD_I64LE, false, file);
  attr_strings(impl_->file, "swept_keys", study.keys, file);

  // Every table's datasets are created at their full length first, then filled block by block:
  // each case built once (the study builds them on demand), each result row parsed once.
  const Id params =
      checked(H5Gcreate2(impl_->file, "parameters", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Gclose, "cannot write " + file + ": group parameters");
  const std::span<const Field> every = fields();
  std::vector<Id> param_sets;
  for (const Field& f : every) {
    param_sets.push_back(create_dataset(params, f.key, H5T_IEEE_F64LE, n, false, file));
    const Id& d = param_sets.back();
    if (*f.unit != '\0') attr_string(d, "unit", f.unit, file);
    attr_string(d, "description", f.description, file);
    attr_string(d, "rule", field_rule(f), file);
    if (f.type == FieldType::choice) {
      std::vector<std::string> names;
      std::string_view all(f.choices);
      for (std::size_t start = 0;;) {
        const std::size_t bar = all.find('|', start);
        names.emplace_back(all.substr(start, bar - start));
        if (bar == std::string_view::npos) break;
        start = bar + 1;
      }
      attr_strings(d, "choices", names, file);
    }
  }

  const Id results =
      checked(H5Gcreate2(impl_->file, "results", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
              "cannot write " + file + ": group results");
  const std::vector<std::string> labels = csv_split(header);
  std::vector<std::string> order;  // the CSV's column order (HDF5 lists members by name)
  for (std::size_t c = 1; c < labels.size(); ++c) order.push_back(split_label(labels[c]).first);
  attr_strings(results, "columns", order, file);
  const Id text_type = string_type();
  std::vector<Id> result_sets(labels.size());  // column 0 is the case index: /case
  std::vector<bool> text(labels.size(), false);
  for (std::size_t c = 1; c < labels.size(); ++c) {
    const auto [name, unit] = split_label(labels[c]);
    const Field* f = find_field(name);
    text[c] = oscidrum::is_text_column(name) ||
              (f && (f->type == FieldType::boolean || f->type == FieldType::choice));
    result_sets[c] =
        create_dataset(results, name, text[c] ? text_type.get() : H5T_IEEE_F64LE, n, false, file);
    if (text[c] || !unit.empty()) attr_string(result_sets[c], "unit", unit, file);
  }

  // Each table's group holds its dimension `case` (a copy of /case, a dimension scale attached
  // to the group's other datasets): netCDF-4 readers take a group's own variable of a dimension's
  // name as its coordinate, so xarray opens /parameters and /results with the coordinate `case`
  // (with the scale in the root only, the groups had none, and a shard's .sel(case=4) picked the
  // row at position 4).
  {
    std::vector<hid_t> tables;
    for (const Id& d : param_sets) tables.push_back(d);
    write_ints(params, "case", cases, H5T_STD_I64LE, false, file);
    const Id param_cases(H5Dopen2(params, "case", H5P_DEFAULT), H5Dclose);
    attach_scale(param_cases, "case", tables, file);
    tables.clear();
    for (std::size_t c = 1; c < labels.size(); ++c) tables.push_back(result_sets[c]);
    write_ints(results, "case", cases, H5T_STD_I64LE, false, file);
    const Id result_cases(H5Dopen2(results, "case", H5P_DEFAULT), H5Dclose);
    attach_scale(result_cases, "case", tables, file);
  }

  // /derived: what the model ran with where a case gives it through other keys: the soil's
  // Kelvin-Voigt coefficients (Table 2 or Appendix B) and the oscillation moment (roller.M0, or
  // 4 m_u e_u e_w nu^2 from roller.unbalance (5); 0 for the vibratory drum).
  constexpr std::size_t kDerived = 5;
  static constexpr const char* kDerivedNames[kDerived] = {"ksh", "ksv", "csh", "csv", "M0"};
  static constexpr const char* kDerivedUnits[kDerived] = {"N/m", "N/m", "N s/m", "N s/m", "N m"};
  static constexpr const char* kDerivedMeaning[kDerived] = {
      "horizontal soil spring used (the soil input's coefficients)", "vertical soil spring used",
      "horizontal soil damper used", "vertical soil damper used",
      "oscillation moment amplitude used (5): roller.M0, or 4 m_u e_u e_w nu^2 with "
      "roller.unbalance; 0 for the vibratory drum"};
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Id derived_group =
      checked(H5Gcreate2(impl_->file, "derived", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
              "cannot write " + file + ": group derived");
  std::vector<Id> derived_sets;
  for (std::size_t j = 0; j < kDerived; ++j) {
    derived_sets.push_back(
        create_dataset(derived_group, kDerivedNames[j], H5T_IEEE_F64LE, n, false, file));
    attr_string(derived_sets.back(), "unit", kDerivedUnits[j], file);
    attr_string(derived_sets.back(), "description", kDerivedMeaning[j], file);
  }
  {
    std::vector<hid_t> tables;
    for (const Id& d : derived_sets) tables.push_back(d);
    write_ints(derived_group, "case", cases, H5T_STD_I64LE, false, file);
    const Id derived_cases(H5Dopen2(derived_group, "case", H5P_DEFAULT), H5Dclose);
    attach_scale(derived_cases, "case", tables, file);
  }
  std::vector<std::vector<double>> derived(kDerived);
  std::vector<std::vector<double>> numbers(std::max(every.size(), labels.size()));
  std::vector<std::vector<std::string>> strings(labels.size());
  for (std::size_t first = 0; first < n; first += kBlockRows) {
    const std::size_t count = std::min(kBlockRows, n - first);
    for (auto& v : numbers) v.clear();
    for (auto& v : derived) v.clear();
    for (std::size_t k = first; k < first + count; ++k) {
      const Case c = study.cases[indices[k]];
      // NaN for a key without effect in the case (its default, written as if used, told
      // another soil or moment than the run's: /derived has those).
      for (std::size_t j = 0; j < every.size(); ++j)
        numbers[j].push_back(key_in_effect(c, every[j].key) ? every[j].get(c) : kNaN);
      const SoilCoefficients soil = soil_coefficients(c.soil, c.roller);
      const bool vibratory = c.roller.type == RollerType::vibratory;
      const double derived_values[kDerived] = {soil.ksh, soil.ksv, soil.csh, soil.csv,
                                               vibratory ? 0.0 : oscillation_moment(c.roller)};
      for (std::size_t j = 0; j < kDerived; ++j) derived[j].push_back(derived_values[j]);
    }
    for (std::size_t j = 0; j < every.size(); ++j)
      write_block(param_sets[j], H5T_NATIVE_DOUBLE, first, count, numbers[j].data(),
                  "cannot write " + file + ": dataset parameters/" + every[j].key);
    for (std::size_t j = 0; j < kDerived; ++j)
      write_block(derived_sets[j], H5T_NATIVE_DOUBLE, first, count, derived[j].data(),
                  "cannot write " + file + ": dataset derived/" + kDerivedNames[j]);

    for (auto& v : numbers) v.clear();
    for (auto& v : derived) v.clear();
    for (auto& v : strings) v.clear();
    for (std::size_t k = first; k < first + count; ++k) {
      const std::vector<std::string> cells = csv_split(row(k));
      for (std::size_t c = 1; c < labels.size(); ++c) {
        const std::string cell = c < cells.size() ? cells[c] : std::string();
        if (text[c]) {
          strings[c].push_back(cell);
          continue;
        }
        char* end = nullptr;
        const double x = std::strtod(cell.c_str(), &end);
        numbers[c].push_back(cell.empty() || *end ? std::nan("") : x);
      }
    }
    for (std::size_t c = 1; c < labels.size(); ++c) {
      const std::string what = "cannot write " + file + ": dataset results/" + order[c - 1];
      if (!text[c]) {
        write_block(result_sets[c], H5T_NATIVE_DOUBLE, first, count, numbers[c].data(), what);
        continue;
      }
      std::vector<const char*> p;
      for (const std::string& v : strings[c]) p.push_back(v.c_str());
      write_block(result_sets[c], text_type, first, count, p.data(), what);
    }
  }
  H5Fflush(impl_->file, H5F_SCOPE_GLOBAL);
  impl_->file.reset();
  // Renamed only over a regular file (or nothing): the target is checked again.
  const std::string target = output_target(impl_->path, true).path;
  if (std::rename(file.c_str(), target.c_str()) != 0)
    throw Error("cannot write " + impl_->path + ": " + std::strerror(errno));
}

void StudyHdf5Writer::discard_partial(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path + ".partial", ec);
}

void merge_hdf5_shards(const std::vector<std::string>& paths, const std::string& out) {
  const QuietErrors quiet;
  std::vector<Id> files;
  std::vector<ShardInfo> infos;
  for (const std::string& p : paths) {
    Id f(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!f.ok()) throw Error("cannot read " + p + " as HDF5");
    std::string shard;
    ShardInfo info;
    try {
      if (read_attr_string(f, "format", p) != kFormat) throw Error("");
      shard = read_attr_string(f, "shard", p);
      info.fingerprint =
          std::strtoull(read_attr_string(f, "study_fingerprint", p).c_str(), nullptr, 16);
      info.n_cases = static_cast<std::size_t>(read_attr_int(f, "n_cases_in_study", p));
    } catch (const Error&) {
      throw Error(p + " is not an HDF5 file of 'oscidrum sweep --hdf5'");
    }
    if (shard.empty())
      throw Error(p +
                  " is not the output of 'oscidrum sweep --shard I/N' (an HDF5 file of a "
                  "whole study)");
    info.shard = parse_shard(shard);
    infos.push_back(info);
    files.push_back(std::move(f));
  }
  check_shard_set(infos, paths);
  const std::size_t total = infos.front().n_cases;

  // Where each case's row is: (file, row).
  std::vector<std::pair<std::size_t, std::size_t>> where(total, {SIZE_MAX, 0});
  for (std::size_t k = 0; k < files.size(); ++k) {
    const Id d(H5Dopen2(files[k], "case", H5P_DEFAULT), H5Dclose);
    if (!d.ok()) throw Error(paths[k] + " is damaged: no /case (an unfinished shard?)");
    const std::vector<std::int64_t> cases = read_ints(d, "cannot read " + paths[k] + ": /case");
    const ShardInfo& s = infos[k];
    const std::size_t expected =
        total / s.shard.count + (s.shard.index - 1 < total % s.shard.count ? 1 : 0);
    if (cases.size() != expected)
      throw Error(paths[k] + " (shard " + s.shard.text() + ") holds " +
                  std::to_string(cases.size()) + " cases, but the shard has " +
                  std::to_string(expected));
    for (std::size_t r = 0; r < cases.size(); ++r) {
      const std::int64_t c = cases[r];
      if (c < 0 || static_cast<std::size_t>(c) >= total ||
          !s.shard.holds(static_cast<std::size_t>(c)) ||
          where[static_cast<std::size_t>(c)].first != SIZE_MAX)
        throw Error(paths[k] + " (shard " + s.shard.text() + ") holds case " + std::to_string(c) +
                    ", which is not one of its cases");
      where[static_cast<std::size_t>(c)] = {k, r};
    }
  }

  OutputFile output(out, true);
  const std::string& tmp = output.write_path();
  {
    Id dst(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (!dst.ok()) throw Error("cannot write " + out);
    Hdf5StudyInfo info{infos.front().fingerprint, total, false, {}};
    write_root_attributes(dst, info, out);
    copy_attributes(files.front(), dst, paths.front());  // swept_keys and anything newer
    std::vector<std::int64_t> all(total);
    for (std::size_t i = 0; i < total; ++i) all[i] = static_cast<std::int64_t>(i);
    write_ints(dst, "case", all, H5T_STD_I64LE, false, out);

    for (const char* group : {"parameters", "derived", "results"}) {
      const Id g0(H5Gopen2(files.front(), group, H5P_DEFAULT), H5Gclose);
      if (!g0.ok()) throw Error(paths.front() + " is damaged: no /" + group);
      const Id g = checked(H5Gcreate2(dst, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                           "cannot write " + out);
      copy_attributes(g0, g, paths.front());
      for (const std::string& name : member_names(g0)) {
        std::vector<Id> src;
        for (std::size_t k = 0; k < files.size(); ++k) {
          const std::string full = std::string(group) + "/" + name;
          src.emplace_back(H5Dopen2(files[k], full.c_str(), H5P_DEFAULT), H5Dclose);
          if (!src.back().ok())
            throw Error(paths[k] + " has other columns than " + paths.front() + " (no /" + full +
                        ")");
        }
        const Id type(H5Dget_type(src.front()), H5Tclose);
        const H5T_class_t cls = H5Tget_class(type);
        const std::string what = "cannot read " + std::string(group) + "/" + name;
        if (cls == H5T_STRING) {
          std::vector<std::vector<std::string>> parts;
          for (const Id& d : src) parts.push_back(read_strings(d, what));
          std::vector<std::string> v(total);
          for (std::size_t i = 0; i < total; ++i) v[i] = parts[where[i].first][where[i].second];
          write_strings(g, name, v, out);
        } else if (cls == H5T_INTEGER) {
          std::vector<std::vector<std::int64_t>> parts;
          for (const Id& d : src) parts.push_back(read_ints(d, what));
          std::vector<std::int64_t> v(total);
          for (std::size_t i = 0; i < total; ++i) v[i] = parts[where[i].first][where[i].second];
          write_ints(g, name, v, H5T_STD_I64LE, false, out);
        } else {
          std::vector<std::vector<double>> parts;
          for (const Id& d : src) parts.push_back(read_doubles(d, what));
          std::vector<double> v(total);
          for (std::size_t i = 0; i < total; ++i) v[i] = parts[where[i].first][where[i].second];
          write_doubles(g, name, v, "", false, out);
        }
        const Id d(H5Dopen2(g, name.c_str(), H5P_DEFAULT), H5Dclose);
        copy_attributes(src.front(), d, paths.front());
      }
    }
    // Each table's group's `case` (merged as its other columns), the dimension scale of the
    // group's other datasets, as in an unsharded file.
    for (const char* group : {"parameters", "derived", "results"}) {
      const Id g(H5Gopen2(dst, group, H5P_DEFAULT), H5Gclose);
      std::vector<Id> open;
      std::vector<hid_t> tables;
      for (const std::string& name : member_names(g)) {
        if (name == "case") continue;
        open.emplace_back(H5Dopen2(g, name.c_str(), H5P_DEFAULT), H5Dclose);
        tables.push_back(open.back());
      }
      const Id case_set(H5Dopen2(g, "case", H5P_DEFAULT), H5Dclose);
      attach_scale(case_set, "case", tables, out);
    }
    const Id cases = checked(H5Gcreate2(dst, "steady_state", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             H5Gclose, "cannot write " + out);
    {
      const Id g0(H5Gopen2(files.front(), "steady_state", H5P_DEFAULT), H5Gclose);
      if (g0.ok()) copy_attributes(g0, cases, paths.front());
    }
    for (std::size_t i = 0; i < total; ++i) {
      const std::string name = "steady_state/" + case_group(i);
      if (H5Lexists(files[where[i].first], name.c_str(), H5P_DEFAULT) <= 0)
        throw Error(paths[where[i].first] + " is damaged: no /" + name);
      check(
          H5Ocopy(files[where[i].first], name.c_str(), dst, name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          "cannot write " + out + ": " + name);
      const Id copied(H5Gopen2(dst, name.c_str(), H5P_DEFAULT), H5Gclose);
      attach_time_scale(copied, out, true);
    }
    H5Fflush(dst, H5F_SCOPE_GLOBAL);
  }
  output.commit();
}

}  // namespace oscidrum::io
