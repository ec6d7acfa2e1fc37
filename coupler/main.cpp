// `coupler`: the coupling daemon (inside an MPMD job) and the checks the
// launcher runs before starting one (validate, plan, post-mortem).
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "daemon.hpp"
#include "driver_catalog.hpp"
#include "pbms/config/workflow.hpp"
#include "pbms/mpi/comm.hpp"
#include "postmortem.hpp"
#include "reference_doc.hpp"
#include "run_record.hpp"

namespace {

std::filesystem::path own_dir() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::current_path() : p.parent_path();
}

// Loads and checks a workflow the way `pbms validate` reports it: every
// error on its own line, nothing else. Returns the workflow or exits 1.
std::optional<pbms::config::Workflow> load_or_report(
    const std::string& config, const std::vector<pbms::config::DriverDescription>& drivers,
    const std::vector<std::string>& overrides) {
  auto r = pbms::config::load_workflow(config, drivers);
  for (const auto& e : r.errors) std::cerr << e.format() << "\n";
  for (const auto& w : r.warnings) std::cerr << w.format() << "\n";
  if (!r.workflow) return std::nullopt;
  bool ok = true;
  for (const auto& o : overrides) {
    if (auto err = pbms::config::apply_rank_override(*r.workflow, drivers, o); !err.empty()) {
      std::cerr << config << ": error: " << err << "\n";
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  return r.workflow;
}

// What the command line says. The subcommands share `config`, `ranks`,
// `resume`, `overwrite` and `run_id`, each bound to one variable.
struct Args {
  std::string drivers_dir = own_dir().string();
  std::string config;
  std::vector<std::string> ranks;
  bool resume = false, overwrite = false;
  bool terminal = false;
  std::string command_line;
  std::string run_id;
  std::string run_dir, mpirun_log;
  int exit_code = 0;
};

CLI::App* add_validate(CLI::App& app, Args& a) {
  auto* validate = app.add_subcommand("validate", "Check a workflow; print every error");
  validate->add_option("config", a.config, "Workflow YAML")->required();
  validate->add_option("--ranks", a.ranks, "Rank override PROGRAM=N");
  return validate;
}

CLI::App* add_plan(CLI::App& app, Args& a) {
  auto* plan = app.add_subcommand(
      "plan", "Validate, check the run directory, then print it and the programs");
  plan->add_option("config", a.config, "Workflow YAML")->required();
  plan->add_option("--ranks", a.ranks, "Rank override PROGRAM=N");
  plan->add_flag("--resume", a.resume, "The run will keep its run directory");
  plan->add_flag("--overwrite", a.overwrite, "The run will replace an earlier run of its name");
  return plan;
}

CLI::App* add_daemon(CLI::App& app, Args& a) {
  auto* daemon = app.add_subcommand("daemon", "Run as the coupling daemon (under mpirun)");
  daemon->add_option("config", a.config, "Workflow YAML")->required();
  daemon->add_option("--ranks", a.ranks, "Rank override PROGRAM=N");
  daemon->add_flag("--tty", a.terminal, "Refresh progress lines in place");
  daemon->add_flag("--resume", a.resume,
                   "Keep the run directory; stages resume what they recorded");
  daemon->add_flag("--overwrite", a.overwrite,
                   "Delete an earlier run of the same name (else the daemon refuses to start)");
  daemon->add_option("--command", a.command_line, "Command line to record in the manifest");
  daemon->add_option("--run-id", a.run_id, "Identity of this job, recorded in the manifest");
  return daemon;
}

CLI::App* add_postmortem(CLI::App& app, Args& a) {
  auto* pm = app.add_subcommand("postmortem", "Record a job that mpirun ended");
  pm->add_option("run_dir", a.run_dir)->required();
  pm->add_option("--exit-code", a.exit_code)->required();
  pm->add_option("--mpirun-log", a.mpirun_log)->required();
  pm->add_option("--run-id", a.run_id,
                 "The job's identity: a run directory of another job is left as it is");
  return pm;
}

int describe_drivers(const std::vector<pbms::config::DriverDescription>& drivers) {
  YAML::Node all;
  for (const auto& d : drivers) all.push_back(pbms::config::to_yaml(d));
  YAML::Emitter e;
  e << all;
  std::cout << e.c_str() << "\n";
  return 0;
}

int validate_workflow(const Args& a, const std::vector<pbms::config::DriverDescription>& drivers) {
  auto wf = load_or_report(a.config, drivers, a.ranks);
  if (!wf) return 1;
  const std::size_t nw = wf->warnings.size();
  const std::string warned =
      nw == 0 ? "" : fmt::format(", {} warning{} above", nw, nw == 1 ? "" : "s");
  std::cout << fmt::format("{}: ok ({} stage{}, run directory {}{})\n", a.config, wf->stages.size(),
                           wf->stages.size() == 1 ? "" : "s", wf->run_dir().string(), warned);
  return 0;
}

int plan_run(const Args& a, const std::vector<pbms::config::DriverDescription>& drivers) {
  auto wf = load_or_report(a.config, drivers, a.ranks);
  if (!wf) return 1;
  const auto existing = a.resume      ? pbms::coupler::ExistingRun::kResume
                        : a.overwrite ? pbms::coupler::ExistingRun::kOverwrite
                                      : pbms::coupler::ExistingRun::kRefuse;
  if (auto refusal = pbms::coupler::existing_run_refusal(*wf, existing); !refusal.empty()) {
    std::cerr << refusal << "\n";
    return 1;
  }
  std::cout << "run_dir " << std::filesystem::absolute(wf->run_dir()).string() << "\n";
  for (const auto& p : wf->programs()) std::cout << "app " << p << " " << wf->ranks[p] << "\n";
  return 0;
}

int run_as_daemon(int argc, char** argv, const Args& a) {
  pbms::mpi::Environment env(argc, argv);
  pbms::coupler::DaemonOptions opt{a.config, a.drivers_dir, a.ranks,        a.terminal,
                                   a.resume, a.overwrite,   a.command_line, a.run_id};
  try {
    return pbms::coupler::run_daemon(opt);
  } catch (const std::exception& e) {
    // The other programs of the MPMD job would wait for the daemon forever.
    std::cerr << "pbms: error: coupler: " << e.what() << "\n" << std::flush;
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  return 0;
}

int run_coupler(int argc, char** argv) {
  CLI::App app{"PBMS coupler: the coupling daemon and pre-launch checks. Users run ./pbms."};
  app.require_subcommand(1);
  Args a;
  app.add_option("--drivers", a.drivers_dir, "Directory holding the *_driver programs");
  auto* validate = add_validate(app, a);
  auto* plan = add_plan(app, a);
  auto* daemon = add_daemon(app, a);
  auto* pm = add_postmortem(app, a);
  auto* reference = app.add_subcommand("reference", "Print the config reference (Markdown)");
  auto* describe = app.add_subcommand("describe", "Print what every driver declares (YAML)");

  CLI11_PARSE(app, argc, argv);

  try {
    if (*pm) return pbms::coupler::postmortem(a.run_dir, a.exit_code, a.mpirun_log, a.run_id);
    if ((*plan || *daemon) && a.resume && a.overwrite) {
      std::cerr << "pbms: error: --resume keeps the run directory and --overwrite replaces it: "
                   "give one of them\n";
      return 1;
    }
    // The daemon asks the drivers for their descriptions itself (each ask
    // starts every driver once).
    if (*daemon) return run_as_daemon(argc, argv, a);
    const auto drivers = pbms::coupler::discover_drivers(a.drivers_dir);
    if (*reference) {
      std::cout << pbms::coupler::config_reference_markdown(drivers);
      return 0;
    }
    if (*describe) return describe_drivers(drivers);
    if (*validate) return validate_workflow(a, drivers);
    if (*plan) return plan_run(a, drivers);
  } catch (const std::exception& e) {
    std::cerr << "pbms: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

// CLI11's set-up may throw (bad_alloc at least): nothing leaves main.
int main(int argc, char** argv) {
  try {
    return run_coupler(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "pbms: error: coupler: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "pbms: error: coupler: an unknown exception\n";
  }
  return 1;
}
