#include "pbms/mpi/mpmd.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <thread>

#include <fmt/format.h>

namespace pbms::mpi {
namespace {
constexpr int kMessageTag = 77;
}

MpmdWorld MpmdWorld::join(Role role) {
  MpmdWorld w;
  int* appnum_attr = nullptr;
  int found = 0;
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_APPNUM, &appnum_attr, &found);
  w.appnum_ = found && appnum_attr ? *appnum_attr : 0;
  MPI_Comm local = MPI_COMM_NULL;
  int world_rank = 0, world_size = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  check(MPI_Comm_split(MPI_COMM_WORLD, w.appnum_, world_rank, &local), "MPI_Comm_split");
  w.local_ = Comm(local);

  const int mine[2] = {w.appnum_, static_cast<int>(role)};
  std::vector<int> all(2 * static_cast<size_t>(world_size));
  check(MPI_Allgather(mine, 2, MPI_INT, all.data(), 2, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  std::map<int, App> apps;
  for (int r = 0; r < world_size; ++r) {
    const int a = all[2 * static_cast<size_t>(r)];
    auto [it, inserted] = apps.try_emplace(a);
    App& app = it->second;
    if (inserted) {
      app.appnum = a;
      app.role = static_cast<Role>(all[2 * static_cast<size_t>(r) + 1]);
      app.leader = r;
      app.first_world_rank = r;
    }
    ++app.size;
  }
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
  auto pause = std::chrono::microseconds(50);
  for (;;) {
    if (auto m = poll(source)) return std::move(*m);
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
}

}  // namespace pbms::mpi
