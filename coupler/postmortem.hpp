// After mpirun has ended a job that the coupler could not finish itself (a
// rank was killed, LAMMPS exited, a node vanished), work out from mpirun's
// output and the manifest who failed where, say so, and record it.
#pragma once

#include <filesystem>
#include <string>

namespace pbms::coupler {

struct DeadRank {
  int world_rank = -1;
  int signal = 0;  // 0 if it exited
  int exit_code = 0;
  std::string signal_name;
};

// Parses Open MPI's report of the first process that ended the job.
DeadRank parse_mpirun_output(const std::string& text);

// Returns the exit code the launcher should use. With a `run_id`, a run
// directory whose manifest is not that job's (an earlier run the daemon
// refused to replace) is left exactly as it is.
int postmortem(const std::filesystem::path& run_dir, int mpirun_exit_code,
               const std::filesystem::path& mpirun_log, const std::string& run_id = {});

}  // namespace pbms::coupler
