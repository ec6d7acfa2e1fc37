// Small RAII layer over the HDF5 C API: every hid_t is closed by its owner,
// so an exception never leaves a file open (and unreadable) behind.
#pragma once

#include <hdf5.h>
#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace pbms::h5 {

class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer);  // throws if id < 0
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      closer_ = o.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  [[nodiscard]] hid_t id() const { return id_; }
  void reset();

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// Updates `path` (one process) without ever having it open for writing:
// the returned file is a copy of `path` (an empty file when it is missing)
// named `path` + ".tmp", and closing the handle renames the copy over
// `path`. A reader of `path` therefore sees the file before or after the
// update, never half of it, and is never in the writer's way (HDF5 1.10
// locks the files it opens: a reader holding `path` open would make an
// in-place writer's open fail, and the other way round). A handle closed
// while an exception unwinds drops the copy and leaves `path` as it was.
Handle open_or_create(const std::string& path);
// With a communicator of more than one rank the file is created collectively
// through MPI-IO, and its handle is not closed while an exception unwinds:
// the close is collective, and the other ranks may never come to it. A
// request that all ranks fail together (StageContext::fail_together) and
// survive would leave such a file open until MPI_Finalize; none writes one
// today.
Handle create_truncate(const std::string& path, MPI_Comm comm = MPI_COMM_SELF);
// An existing file opened to write, collectively over `comm` as create_truncate.
Handle open_read_write(const std::string& path, MPI_Comm comm = MPI_COMM_SELF);
// The group at `path` (slash separated), creating missing parents.
Handle require_group(hid_t parent, const std::string& path);
void delete_link_if_exists(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& name);

void write_attribute(hid_t obj, const std::string& name, const std::string& value);
// A variable-length ASCII string: h5py reads it as `str` (a fixed-length one
// as `bytes`), which is what MDAnalysis' H5MD reader looks up units with.
void write_vlen_attribute(hid_t obj, const std::string& name, const std::string& value);
void write_attribute(hid_t obj, const std::string& name, double value);
// A fixed-length string attribute, as write_attribute writes it; throws
// pbms::Error when `obj` has no string attribute `name`.
std::string read_string_attribute(hid_t obj, const std::string& name);
void write_attribute(hid_t obj, const std::string& name, const std::vector<int>& value);
// 1-D double dataset with a "unit" attribute.
void write_vector(hid_t parent, const std::string& name, const std::vector<double>& data,
                  const std::string& unit);
void write_scalar(hid_t parent, const std::string& name, double value, const std::string& unit);

}  // namespace pbms::h5
