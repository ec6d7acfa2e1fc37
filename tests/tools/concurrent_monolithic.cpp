// The monolithic reference of a concurrent DPD/MPM stage: the stage of a
// finished run (its resolved config.yaml), built as dpd_driver and
// mpm_driver build their parts (DpdPartOfBody, MpmPartOfBody), but both in
// this one process, joined by an InProcessLink, with no band and no reach
// to leave anything out; an initial.from_stage comes from the run
// directory, and the stage loops' thermostat and gas heat bath act after
// each step as there. Advances the stage's steps and writes every
// particle's and point's id, position and velocity, one per line, at full
// precision, for tests/integration/concurrent_split_drivers.sh to compare
// with what the two drivers wrote.
//
//   concurrent_monolithic RUN_DIR STAGE OUT
#include <mpi.h>

#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/in_process_link.hpp"
#include "stage/dpd_model.hpp"
#include "stage/dpd_part_of_body.hpp"
#include "stage/mpm_part_of_body.hpp"

namespace {

using Row = std::array<double, 6>;  // x, v

YAML::Node stage_node(const YAML::Node& config, const std::string& name) {
  for (const auto& s : config["stages"]) {
    if (s["name"].as<std::string>() == name) return s;
  }
  throw std::runtime_error(fmt::format("no stage '{}' in the run's config.yaml", name));
}

std::map<std::int64_t, Row> advance(const YAML::Node& config, const std::string& stage) {
  const YAML::Node params = stage_node(config, stage);
  if (params["kind"].as<std::string>() != "concurrent") {
    throw std::runtime_error(fmt::format("stage '{}' is not a concurrent stage", stage));
  }
  const YAML::Node material = config["materials"][params["material"].as<std::string>()];
  pbms::dpd::DpdPartOfBody dpd(MPI_COMM_SELF, params, material,
                               config["run"]["seed"].as<std::uint64_t>(), stage);
  const pbms::coupling::ConcurrentParams& cp = dpd.params();
  pbms::mpm::MpmPartOfBody mpm(MPI_COMM_SELF, cp, dpd.handover());
  pbms::coupling::InProcessLink link(dpd.side(), mpm.side());
  pbms::coupling::CouplingScheme scheme({&dpd.side(), &mpm.side()}, link, cp.interface, cp.fields(),
                                        cp.move);
  for (std::int64_t n = 1; n <= cp.steps; ++n) {
    dpd.ramp_grips(n);
    mpm.ramp_grips(n);
    scheme.step();
    // What the drivers' stage loops add after each step.
    if (cp.thermostat) dpd.engine().berendsen(cp.thermostat->first, cp.thermostat->second, true);
    mpm.hold_gas_temperature(n);
  }

  std::map<std::int64_t, Row> out;
  const auto& p = dpd.engine().particles();
  for (std::size_t i = 0; i < dpd.engine().owned(); ++i) {
    out[p.id[i]] = {p.x[i][0], p.x[i][1], p.x[i][2], p.v[i][0], p.v[i][1], p.v[i][2]};
  }
  const auto& q = mpm.engine().points();
  for (std::size_t i = 0; i < q.size(); ++i) {
    out[q.id[i]] = {q.x[i][0], q.x[i][1], q.x[i][2], q.v[i][0], q.v[i][1], q.v[i][2]};
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: concurrent_monolithic RUN_DIR STAGE OUT\n");
    return 2;
  }
  MPI_Init(&argc, &argv);
  int rc = 0;
  try {
    const YAML::Node config = YAML::LoadFile(std::string(argv[1]) + "/config.yaml");
    pbms::dpd::use_run_directory(argv[1]);  // an initial.from_stage's state
    const auto rows = advance(config, argv[2]);
    std::FILE* f = std::fopen(argv[3], "w");
    if (f == nullptr) throw std::runtime_error(fmt::format("cannot write {}", argv[3]));
    for (const auto& [id, r] : rows) {
      std::fprintf(f, "%lld %.17g %.17g %.17g %.17g %.17g %.17g\n", static_cast<long long>(id),
                   r[0], r[1], r[2], r[3], r[4], r[5]);
    }
    std::fclose(f);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "concurrent_monolithic: %s\n", e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
