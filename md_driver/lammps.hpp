// RAII ownership of one LAMMPS instance on the driver's communicator. Every
// command is recorded, so the exact input each stage ran can be written out
// and replayed with a plain `lmp -in` (the side-by-side check in tests/).
#pragma once

#define LAMMPS_LIB_MPI 1
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pbms::md {

class Lammps {
 public:
  // `append`: a resumed stage goes on with the log of the run it resumes.
  Lammps(MPI_Comm comm, const std::filesystem::path& log_file, bool append = false);
  ~Lammps();
  Lammps(const Lammps&) = delete;
  Lammps& operator=(const Lammps&) = delete;

  void command(const std::string& cmd);
  void comment(const std::string& text);  // recorded only

  // LAMMPS' own restart file of the system now (collective): atoms, box,
  // groups, and the state of the fixes that keep one (Nose-Hoover's
  // thermostat and barostat variables, fix deform's initial box). Recorded
  // as a comment: a replay of the script needs no file. The fixes in
  // `drop` are deleted first: write_restart initialises LAMMPS between
  // runs, where a fix vector made after step 0 fails to size its storage.
  // So the instance must not run on after it.
  void write_restart(const std::filesystem::path& file, const std::vector<std::string>& drop);
  // Reads one into this instance (collective), not recorded (the stage
  // takes the script of the run that wrote it: adopt_script()).
  void read_restart(const std::filesystem::path& file);

  // Runs `steps` MD steps in chunks of `chunk`, calling `after_chunk(done)`
  // between chunks (progress, trajectory frames). Recorded chunk by chunk, as
  // it ran, so that a plain `lmp -in` of the script on as many ranks repeats
  // the very commands and follows the same trajectory to the last bit (a run
  // on another rank count does not: the sums go in another order, and MD
  // grows that round-off).
  void run(int64_t steps, int64_t chunk, const std::function<void(int64_t)>& after_chunk);
  // The rest of a run whose whole extent is steps `begin` to `end` (as
  // run() gave it), from the current step: a run resumed from a restart
  // file goes on with the chunks and the extent of the run that wrote it.
  void run_rest(int64_t begin, int64_t end, int64_t chunk,
                const std::function<void(int64_t)>& after_chunk);

  [[nodiscard]] double thermo(const std::string& keyword) const;
  [[nodiscard]] double variable(const std::string& name) const;  // equal-style
  // Rows of a global array fix (fix vector), `columns` values per row.
  [[nodiscard]] std::vector<std::vector<double>> fix_array(const std::string& id,
                                                           int columns) const;
  // Per-atom "x" or "v" of all atoms, ordered by atom id (every rank gets it).
  [[nodiscard]] std::vector<double> gather(const std::string& name) const;
  [[nodiscard]] int64_t natoms() const;
  [[nodiscard]] int version() const;

  void write_script(const std::filesystem::path& path, const std::string& header) const;
  [[nodiscard]] const std::vector<std::string>& script() const { return script_; }
  // Takes `earlier` (the commands of the run a restart file came from, up
  // to it) as the script so far, in place of the commands that read the
  // restart file: the script written at the end replays the whole stage.
  void adopt_script(std::vector<std::string> earlier) { script_ = std::move(earlier); }

 private:
  void* handle_ = nullptr;
  std::vector<std::string> script_;
};

}  // namespace pbms::md
