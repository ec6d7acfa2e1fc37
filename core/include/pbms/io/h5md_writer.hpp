// Particle trajectories in H5MD 1.1, written so that MDAnalysis' H5MD reader
// opens them with its defaults (tests/integration/readers_mdanalysis.py
// checks every frame); OVITO does not read H5MD, `./pbms export` turns them into
// extended XYZ. All ranks of `comm` call every method; each passes its own
// particles, and the rows are laid out by rank order (offsets from an
// exclusive scan), so the file is the same whatever the decomposition as
// long as each rank's slice is in global-id order.
//
// Layout: particles/all/{position,velocity,force,internal_energy} as time
// series (step, time, value), particles/all/box/edges as a time series of
// diagonal 3 x 3 matrices (MDAnalysis reads the vector form as a zero box),
// particles/all/{id,species} fixed. Unit attributes are variable-length
// ASCII strings in MDAnalysis' spelling: Angstrom, ps, Angstrom ps-1, eV.
// The units module of H5MD asks for fixed-length strings, but h5py reads
// those as bytes, which MDAnalysis cannot look up. MDAnalysis has no
// eV-based force unit, so forces are stored in kJ mol-1 Angstrom-1
// (converted from the eV/angstrom they are given in).
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pbms/io/hdf5.hpp"

namespace pbms {

class H5mdWriter {
 public:
  struct Options {
    std::string path;
    std::string creator = "pbms";
    std::string creator_version;
    std::array<bool, 3> periodic = {true, true, true};
    // Values in LAMMPS metal units, labelled as such. false: values in a
    // consistent unit system of the user's (an MPM run), written with no
    // unit attributes and no conversion.
    bool metal_units = true;
    bool velocities = false;
    bool forces = false;           // particles/all/force, given in eV/angstrom
    bool internal_energy = false;  // particles/all/internal_energy, eV
  };
  // `ids` and `species` are this rank's particles; the count is fixed.
  H5mdWriter(MPI_Comm comm, const Options& opt, const std::vector<int64_t>& ids,
             const std::vector<int>& species);

  // `positions` (and `velocities`, `forces` when enabled) hold 3 values per
  // local particle, `internal_energy` one, in the same order as the ids
  // given to the constructor. Arrays of disabled series are ignored. The
  // box is rectangular: `box_edges` are its three edge lengths.
  void write_frame(int64_t step, double time_ps, const std::array<double, 3>& box_edges,
                   const std::vector<double>& positions, const std::vector<double>& velocities = {},
                   const std::vector<double>& forces = {},
                   const std::vector<double>& internal_energy = {});
  [[nodiscard]] int64_t frames() const { return frames_; }

 private:
  struct TimeSeries {
    h5::Handle group, step, time, value;
  };
  // `unit` (null: none, and none on time either) goes into the attribute
  // `unit_attribute` of the values.
  TimeSeries make_series(hid_t parent, const std::string& name, int rank_dims, hsize_t n,
                         const char* unit, const char* unit_attribute = "unit");
  void append(TimeSeries& ts, int64_t step, double time, const double* data, hsize_t n_local,
              hsize_t offset, hsize_t n_total, hsize_t width);

  MPI_Comm comm_;
  Options opt_;
  h5::Handle file_;
  h5::Handle dxpl_;
  TimeSeries edges_, position_, velocity_, force_, internal_energy_;
  hsize_t n_local_ = 0, offset_ = 0, n_total_ = 0;
  int64_t frames_ = 0;
};

}  // namespace pbms
