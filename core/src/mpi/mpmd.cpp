#include "pbms/mpi/mpmd.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "pbms/mpi/polling_pause.hpp"

namespace pbms::mpi {
namespace {
constexpr int kMessageTag = 77;

// Which app (program) of the job this process belongs to. mpirun numbers the
// programs of its command line and tells each process through MPI_APPNUM.
// srun --multi-prog does not: under Slurm's PMIx every process reads
// MPI_APPNUM 0. So a launcher may say it instead, in the environment variable
// PBMS_APP (a number per program; `./pbms run --slurm` writes it into the
// multi-prog file), and that takes precedence. Without it, the split is
// MPI_APPNUM's, as it always was.
int app_number() {
  if (const char* env = std::getenv("PBMS_APP"); env != nullptr && *env != '\0') {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(env, &end, 10);
    if (*end != '\0' || errno != 0 || v < 0 || v > 255) {
      throw Error(fmt::format("PBMS_APP='{}' is not a program number (0 to 255)", env));
    }
    return static_cast<int>(v);
  }
  int* appnum_attr = nullptr;
  int found = 0;
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_APPNUM, &appnum_attr, &found);
  return found && appnum_attr ? *appnum_attr : 0;
}

// A number for this process's executable (FNV-1a of its file name), so that
// two different programs given one app number are noticed.
int program_id() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec).filename().string();
  uint32_t h = 2166136261u;
  for (const unsigned char c : exe) h = (h ^ c) * 16777619u;
  return static_cast<int>(h & 0x7fffffffu);
}
}  // namespace

MpmdWorld MpmdWorld::join(Role role) {
  MpmdWorld w;
  w.appnum_ = app_number();
  int world_rank = 0, world_size = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);

  // Everyone's app number, role and program first, so that a launch that
  // lumps different programs into one app fails here, on every rank alike,
  // with a message, instead of hanging in a handshake later.
  constexpr size_t kFields = 3;
  const int mine[kFields] = {w.appnum_, static_cast<int>(role), program_id()};
  std::vector<int> all(kFields * static_cast<size_t>(world_size));
  check(MPI_Allgather(mine, kFields, MPI_INT, all.data(), kFields, MPI_INT, MPI_COMM_WORLD),
        "MPI_Allgather");
  const auto field = [&](int r, size_t f) { return all[kFields * static_cast<size_t>(r) + f]; };
  std::map<int, App> apps;
  for (int r = 0; r < world_size; ++r) {
    const int a = field(r, 0);
    auto [it, inserted] = apps.try_emplace(a);
    App& app = it->second;
    if (inserted) {
      app.appnum = a;
      app.role = static_cast<Role>(field(r, 1));
      app.leader = r;
      app.first_world_rank = r;
    } else if (field(app.leader, 1) != field(r, 1) || field(app.leader, 2) != field(r, 2)) {
      throw Error(fmt::format(
          "world ranks {} and {} run different programs but have the same app number {}; "
          "under srun, where MPI_APPNUM is 0 everywhere, give each program its own PBMS_APP "
          "(the multi-prog file of ./pbms run --slurm does)",
          app.leader, r, a));
    }
    ++app.size;
  }

  MPI_Comm local = MPI_COMM_NULL;
  check(MPI_Comm_split(MPI_COMM_WORLD, w.appnum_, world_rank, &local), "MPI_Comm_split");
  w.local_ = Comm(local);
  for (auto& [a, app] : apps) w.apps_.push_back(app);
  const auto n_couplers = std::count_if(w.apps_.begin(), w.apps_.end(),
                                        [](const App& a) { return a.role == Role::kCoupler; });
  if (n_couplers != 1) {
    throw Error(
        fmt::format("this MPI job has {} coupler programs; it needs exactly one "
                    "(start jobs with ./pbms run)",
                    n_couplers));
  }
  return w;
}

const App& MpmdWorld::coupler() const {
  for (const auto& a : apps_) {
    if (a.role == Role::kCoupler) return a;
  }
  throw Error("no coupler in this job");
}

std::vector<App> MpmdWorld::drivers() const {
  std::vector<App> out;
  for (const auto& a : apps_) {
    if (a.role == Role::kDriver) out.push_back(a);
  }
  return out;
}

Comm MpmdWorld::connect(const App& remote) const {
  const int lo = std::min(appnum_, remote.appnum);
  const int hi = std::max(appnum_, remote.appnum);
  const int tag = 1000 + lo * 97 + hi;
  MPI_Comm inter = MPI_COMM_NULL;
  check(MPI_Intercomm_create(local_.get(), 0, MPI_COMM_WORLD, remote.leader, tag, &inter),
        "MPI_Intercomm_create");
  MPI_Comm_set_errhandler(inter, MPI_ERRORS_RETURN);
  return Comm(inter);
}

void Channel::send(const protocol::Message& m, int remote_rank) const {
  const auto bytes = protocol::pack(m);
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, remote_rank, kMessageTag,
                 comm_.get()),
        "MPI_Send");
}

std::optional<protocol::Message> Channel::poll(int* source) const {
  int flag = 0;
  MPI_Status st;
  check(MPI_Iprobe(MPI_ANY_SOURCE, kMessageTag, comm_.get(), &flag, &st), "MPI_Iprobe");
  if (!flag) return std::nullopt;
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  std::vector<std::byte> buf(static_cast<size_t>(count));
  check(MPI_Recv(buf.data(), count, MPI_BYTE, st.MPI_SOURCE, kMessageTag, comm_.get(),
                 MPI_STATUS_IGNORE),
        "MPI_Recv");
  if (source) *source = st.MPI_SOURCE;
  return protocol::unpack(buf.data(), buf.size());
}

protocol::Message Channel::receive(int* source) const {
  PollingPause pause;
  for (;;) {
    if (auto m = poll(source)) return std::move(*m);
    pause.sleep();
  }
}

}  // namespace pbms::mpi
