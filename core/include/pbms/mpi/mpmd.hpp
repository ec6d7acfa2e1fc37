// How the programs of one MPMD job find each other. Every process splits
// MPI_COMM_WORLD by its app number into its program's communicator and learns
// which apps exist; who is who is settled by the handshake (Hello), never by
// the order of the mpirun command line. The app number is the environment
// variable PBMS_APP where the launcher sets it (srun --multi-prog, which
// leaves MPI_APPNUM 0 for everyone), else MPI_APPNUM (mpirun).
#pragma once

#include <optional>
#include <vector>

#include "pbms/mpi/comm.hpp"
#include "pbms/protocol/messages.hpp"

namespace pbms::mpi {

enum class Role : int { kCoupler = 0, kDriver = 1 };

struct App {
  int appnum = 0;
  Role role = Role::kDriver;
  int leader = 0;  // world rank of the app's rank 0
  int size = 0;
  int first_world_rank = 0;
};

class MpmdWorld {
 public:
  // Collective over MPI_COMM_WORLD.
  static MpmdWorld join(Role role);

  [[nodiscard]] const Comm& local() const { return local_; }
  [[nodiscard]] int appnum() const { return appnum_; }
  [[nodiscard]] const std::vector<App>& apps() const { return apps_; }
  [[nodiscard]] const App& coupler() const;
  [[nodiscard]] std::vector<App> drivers() const;

  // Intercommunicator between this app and `remote`. Collective over both
  // apps' processes; every process must call connect() for the same pairs in
  // the same global order (coupler-driver first, then driver pairs by appnum).
  [[nodiscard]] Comm connect(const App& remote) const;

 private:
  Comm local_;
  int appnum_ = 0;
  std::vector<App> apps_;
};

// A typed message channel over an intercommunicator.
class Channel {
 public:
  Channel() = default;
  explicit Channel(Comm inter) : comm_(std::move(inter)) {}

  void send(const protocol::Message& m, int remote_rank) const;
  // Non-blocking: a message from any remote rank, if one is waiting.
  std::optional<protocol::Message> poll(int* source = nullptr) const;
  // Waits (gently) for the next message from any remote rank.
  protocol::Message receive(int* source = nullptr) const;
  [[nodiscard]] const Comm& comm() const { return comm_; }

 private:
  Comm comm_;
};

}  // namespace pbms::mpi
