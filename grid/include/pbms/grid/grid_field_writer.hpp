// Nodal fields of the MPM background grid as a time series ParaView opens:
// `<base>.h5` holds the data, `<base>.xdmf` (XDMF 3) describes it as a
// temporal collection of 3DCoRectMesh grids. The HDF5 file is the record;
// the XDMF file is derived from it and is rewritten whole after each frame,
// by rank 0, through a temporary file and a rename, so a viewer polling it
// never sees a half-written file nor a frame whose data is not yet flushed.
//
// All ranks of `comm` call every method. Each rank passes the nodes it owns;
// the owned boxes must tile the grid's nodes exactly. Argument errors are
// agreed on collectively, so that every rank throws the same pbms::Error
// instead of one rank leaving the others stuck in a collective HDF5 call.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "pbms/grid/regular_grid.hpp"
#include "pbms/io/hdf5.hpp"

namespace pbms {

class GridFieldWriter {
 public:
  struct Field {
    // The HDF5 dataset name and the array name shown in ParaView; letters,
    // digits, '_', '-' and '.', not starting with a digit, '-' or '.'.
    std::string name;
    std::string unit;
    int components = 1;  // 1 (scalar) or 3 (vector)
    // components * owned.count() values over the owned box: i fastest,
    // components interleaved. Unused (may be null) when the box is empty.
    const double* data = nullptr;
  };

  // Truncates `<base>.h5` and removes a stale `<base>.xdmf`. `comm` must
  // outlive the writer.
  GridFieldWriter(MPI_Comm comm, const std::string& base, const grid::RegularGrid& grid,
                  const grid::NodeBox& owned);
  // A run resumed after `last_step` (a checkpoint's) goes on with the file
  // it wrote: the frames after last_step are unlinked, the XDMF file lists
  // the kept ones again, and the next write_frame appends. The ranks and
  // their boxes may differ from the earlier run's. Collective; throws
  // pbms::Error on every rank when the file cannot be read.
  static std::unique_ptr<GridFieldWriter> reopen(MPI_Comm comm, const std::string& base,
                                                 const grid::RegularGrid& grid,
                                                 const grid::NodeBox& owned,
                                                 std::int64_t last_step);

  // Writes /step_<step>/<name> for each field, of global shape (nz, ny, nx)
  // or (nz, ny, nx, 3): z slowest, as XDMF wants. Steps must be unique;
  // the fields may differ from frame to frame.
  void write_frame(std::int64_t step, double time, const std::vector<Field>& fields);

  [[nodiscard]] std::int64_t frames() const { return frames_; }
  [[nodiscard]] const std::string& h5_path() const { return h5_path_; }
  [[nodiscard]] const std::string& xdmf_path() const { return xdmf_path_; }

 private:
  struct NoFileYet {};
  GridFieldWriter(MPI_Comm comm, const std::string& base, const grid::RegularGrid& grid,
                  const grid::NodeBox& owned, NoFileYet);
  // The checks every constructor makes of its arguments (collective).
  void check_arguments(const std::string& base) const;
  void make_transfer_list();
  // Rank 0: the kept frames' XML and steps, and the later ones' groups.
  struct FramesOnFile {
    std::vector<std::int64_t> kept, dropped;
    std::vector<std::string> xml;
  };
  [[nodiscard]] FramesOnFile frames_on_file(std::int64_t last_step) const;
  // Throws on every rank if any rank's arguments are bad or differ from
  // another rank's.
  void check_frame(std::int64_t step, double time, const std::vector<Field>& fields) const;
  [[nodiscard]] std::string frame_error(std::int64_t step, double time,
                                        const std::vector<Field>& fields) const;
  // The first failure on this rank, or empty.
  [[nodiscard]] std::string write_datasets(hid_t group, std::int64_t step,
                                           const std::vector<Field>& fields) const;
  void publish_frame(std::int64_t step, double time, const std::vector<Field>& fields);
  [[nodiscard]] std::string frame_xml(std::int64_t step, double time,
                                      const std::vector<Field>& fields) const;
  void write_xdmf() const;

  MPI_Comm comm_;
  int rank_ = 0;
  grid::RegularGrid grid_;
  grid::NodeBox owned_;
  std::string h5_path_, xdmf_path_, h5_name_;
  h5::Handle file_;
  h5::Handle dxpl_;
  std::set<std::int64_t> steps_;
  // Rank 0 only: one <Grid> element per frame, kept so that rewriting the
  // XDMF file costs no HDF5 reads.
  std::vector<std::string> frame_xml_;
  std::int64_t frames_ = 0;
};

}  // namespace pbms
