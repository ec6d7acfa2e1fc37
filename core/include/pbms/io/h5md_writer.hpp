// Particle trajectories in H5MD 1.1, written so that MDAnalysis' H5MD reader
// opens them with its defaults (tests/integration/readers_mdanalysis.py
// checks every frame); OVITO does not read H5MD, `./pbms export` turns them into
// extended XYZ. All ranks of `comm` call every method; each passes the
// particles it holds at the time, in any order. A particle's row is its place
// among all ids in ascending order, the same in every frame wherever the
// particle has migrated, so the file is the same whatever the decomposition.
// No rank gathers every particle: the rows are cut into one block per
// rank, each rank's particles go to the ranks whose blocks hold their rows
// (one all-to-all exchange per dataset), and every rank writes its block as
// one hyperslab in a collective MPI-IO write.
//
// Layout: particles/all/{position,velocity,force,internal_energy} as time
// series (step, time, value), particles/all/box/edges as a time series of
// diagonal 3 x 3 matrices (MDAnalysis reads the vector form as a zero box),
// particles/all/{id,species} fixed. Unit attributes are variable-length
// ASCII strings in MDAnalysis' spelling: Angstrom, ps, Angstrom ps-1, eV.
// The units module of H5MD asks for fixed-length strings, but h5py reads
// those as bytes, which MDAnalysis cannot look up. MDAnalysis has no
// eV-based force unit: forces stay in eV/angstrom, their unit under
// `pbms_unit` rather than `unit`.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pbms/io/hdf5.hpp"
#include "pbms/mpi/id_rows.hpp"

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
  // `ids` and `species` are this rank's particles, any order; together the
  // ranks' ids are the file's particles, each id on one rank.
  H5mdWriter(MPI_Comm comm, const Options& opt, const std::vector<int64_t>& ids,
             const std::vector<int>& species);

  // `ids` are the particles this rank holds now (any count, any order, all
  // ranks together holding every particle once); `positions` (and
  // `velocities`, `forces` when enabled) hold 3 values per id,
  // `internal_energy` one, in the order of `ids`. Arrays of disabled series
  // are ignored. The box is rectangular: `box_edges` are its three edge
  // lengths.
  void write_frame(int64_t step, double time_ps, const std::array<double, 3>& box_edges,
                   const std::vector<int64_t>& ids, const std::vector<double>& positions,
                   const std::vector<double>& velocities = {},
                   const std::vector<double>& forces = {},
                   const std::vector<double>& internal_energy = {});
  [[nodiscard]] int64_t frames() const { return frames_; }

  // Goes on with the file `opt.path` a run of the same particles wrote
  // (`ids` as for the constructor, on any rank count): its frames up to
  // `last_step` are kept, later ones dropped, so that a run resumed from a
  // checkpoint after `last_step` writes them again and the file ends as an
  // uninterrupted run's. The kept frames are copied into a new file of the
  // same name. Collective. Throws pbms::Error when the file holds another
  // number of particles.
  static std::unique_ptr<H5mdWriter> reopen(MPI_Comm comm, const Options& opt,
                                            const std::vector<int64_t>& ids, int64_t last_step);

 private:
  struct TimeSeries {
    h5::Handle group, step, time, value;
  };

  // `unit` (null: none, and none on time either) goes into the attribute
  // `unit_attribute` of the values.
  TimeSeries make_series(hid_t parent, const std::string& name, int rank_dims, hsize_t n,
                         const char* unit, const char* unit_attribute = "unit");
  // Appends a frame to `ts`: `data` holds rows [offset, offset + n_local),
  // `width` values each. Rank 0 writes step and time.
  void append(TimeSeries& ts, int64_t step, double time, const std::vector<double>& data,
              hsize_t n_local, hsize_t offset, hsize_t n_total, hsize_t width);

  MPI_Comm comm_;
  int rank_ = 0;
  Options opt_;
  mpi::IdRows rows_;
  mpi::RowBlocks blocks_;
  h5::Handle file_;
  h5::Handle dxpl_;
  TimeSeries edges_, position_, velocity_, force_, internal_energy_;
  hsize_t n_total_ = 0;
  int64_t frames_ = 0;
};

}  // namespace pbms
