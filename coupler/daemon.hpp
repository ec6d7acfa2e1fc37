// The coupling daemon: the one coupler process of an MPMD job. It shakes
// hands with every driver, then walks the workflow's stages, sending each to
// its driver and recording progress, results and failures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pbms::coupler {

struct DaemonOptions {
  std::string config;
  std::filesystem::path drivers_dir;
  std::vector<std::string> rank_overrides;
  bool terminal = false;
  bool resume = false;     // keep the run directory; stages pick up what they recorded
  bool overwrite = false;  // replace an earlier run of the same name (else refuse)
  std::string command_line;
  std::string run_id;  // recorded in the manifest, for `coupler postmortem`
};

// Called between MPI_Init and MPI_Finalize. Returns the exit code.
int run_daemon(const DaemonOptions& opt);

}  // namespace pbms::coupler
