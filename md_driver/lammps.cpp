#include "lammps.hpp"

#include <library.h>

#include <fstream>

#include <fmt/format.h>

#include "pbms/driver/stage_kind.hpp"
#include "pbms/error.hpp"

namespace pbms::md {
namespace {

// The log of the instance that is running now: where LAMMPS writes its
// "ERROR: ..." line before it gives up on the process.
std::string g_current_log;

std::string describe_lammps_exit() {
  std::ifstream in(g_current_log);
  std::string line, error, last_command;
  while (std::getline(in, line)) {
    if (line.rfind("ERROR", 0) == 0) error = line;
    if (line.rfind("Last command:", 0) == 0) last_command = line;
  }
  if (error.empty()) return {};
  return fmt::format("LAMMPS stopped: {}{} (log: {})", error,
                     last_command.empty() ? "" : "; " + last_command, g_current_log);
}

}  // namespace

Lammps::Lammps(MPI_Comm comm, const std::filesystem::path& log_file, bool append) {
  std::string log = log_file.string();
  g_current_log = log;
  set_unexpected_finalize_handler(&describe_lammps_exit);
  const char* args[] = {"md_driver", "-log", append ? "none" : log.c_str(),
                        "-screen",   "none", "-nocite"};
  handle_ = lammps_open(6, const_cast<char**>(args), comm, nullptr);
  if (!handle_) throw Error("LAMMPS could not be started");
  if (append) lammps_command(handle_, fmt::format("log {} append", log).c_str());
}

Lammps::~Lammps() {
  if (handle_) lammps_close(handle_);
}

void Lammps::command(const std::string& cmd) {
  script_.push_back(cmd);
  // This LAMMPS build has no C++ exceptions: an error ends the process and
  // leaves "ERROR: ..." in the log, which the launcher's post-mortem reports.
  lammps_command(handle_, cmd.c_str());
}

void Lammps::comment(const std::string& text) {
  script_.push_back("# " + text);
}

void Lammps::write_restart(const std::filesystem::path& file,
                           const std::vector<std::string>& drop) {
  comment("write_restart: a checkpoint of the stage");
  for (const auto& fix : drop) lammps_command(handle_, ("unfix " + fix).c_str());
  lammps_command(handle_, fmt::format("write_restart {}", file.string()).c_str());
}

void Lammps::read_restart(const std::filesystem::path& file) {
  lammps_command(handle_, fmt::format("read_restart {}", file.string()).c_str());
}

void Lammps::run(int64_t steps, int64_t chunk, const std::function<void(int64_t)>& after_chunk) {
  const auto begin = static_cast<int64_t>(lammps_get_thermo(handle_, "step"));
  run_rest(begin, begin + steps, chunk, after_chunk);
}

void Lammps::run_rest(int64_t begin, int64_t end, int64_t chunk,
                      const std::function<void(int64_t)>& after_chunk) {
  chunk = std::max<int64_t>(1, chunk);
  const auto now = static_cast<int64_t>(lammps_get_thermo(handle_, "step"));
  int64_t done = now - begin;
  bool first = true;
  while (begin + done < end) {
    const int64_t n = std::min(chunk, end - begin - done);
    // start/stop tell fixes (fix vector storage, ramps) the whole run's
    // extent. Setup (neighbour lists, forces) once; later chunks continue
    // the same trajectory without redoing it.
    const std::string cmd =
        fmt::format("run {} start {} stop {} pre {} post no", n, begin, end, first ? "yes" : "no");
    script_.push_back(cmd);
    lammps_command(handle_, cmd.c_str());
    first = false;
    done += n;
    if (after_chunk) after_chunk(done);
  }
}

double Lammps::thermo(const std::string& keyword) const {
  return lammps_get_thermo(handle_, keyword.c_str());
}

double Lammps::variable(const std::string& name) const {
  auto* p = static_cast<double*>(lammps_extract_variable(handle_, name.c_str(), nullptr));
  if (!p) throw Error(fmt::format("LAMMPS variable '{}' is not defined", name));
  const double v = *p;
  lammps_free(p);
  return v;
}

std::vector<std::vector<double>> Lammps::fix_array(const std::string& id, int columns) const {
  std::vector<std::vector<double>> rows;
  auto* nrows_p = static_cast<int*>(
      lammps_extract_fix(handle_, id.c_str(), LMP_STYLE_GLOBAL, LMP_SIZE_ROWS, 0, 0));
  if (!nrows_p) throw Error(fmt::format("LAMMPS fix '{}' has no global array", id));
  const int nrows = *nrows_p;
  for (int i = 0; i < nrows; ++i) {
    std::vector<double> row;
    for (int j = 0; j < columns; ++j) {
      auto* v = static_cast<double*>(
          lammps_extract_fix(handle_, id.c_str(), LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, i, j));
      if (!v) throw Error(fmt::format("LAMMPS fix '{}' has no element ({}, {})", id, i, j));
      row.push_back(*v);
      lammps_free(v);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<double> Lammps::gather(const std::string& name) const {
  std::vector<double> out(static_cast<size_t>(3 * natoms()));
  lammps_gather_atoms(handle_, const_cast<char*>(name.c_str()), 1, 3, out.data());
  return out;
}

int64_t Lammps::natoms() const {
  return static_cast<int64_t>(lammps_get_natoms(handle_));
}

int Lammps::version() const {
  return lammps_version(handle_);
}

void Lammps::write_script(const std::filesystem::path& path, const std::string& header) const {
  std::ofstream out(path);
  out << "# " << header << "\n";
  out << "# Written by PBMS md_driver; run it with: lmp -in " << path.filename().string() << "\n";
  for (const auto& c : script_) out << c << "\n";
}

}  // namespace pbms::md
