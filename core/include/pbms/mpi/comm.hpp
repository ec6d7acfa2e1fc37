// RAII ownership of MPI communicators and a CPU-friendly way to wait.
#pragma once

#include <mpi.h>

#include <string>
#include <utility>

namespace pbms::mpi {

// Owns MPI_Init/MPI_Finalize for one program.
class Environment {
 public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;
};

// A communicator that frees itself unless it is a predefined one.
class Comm {
 public:
  Comm() = default;
  explicit Comm(MPI_Comm c, bool owned = true) : comm_(c), owned_(owned) {}
  ~Comm() { reset(); }
  Comm(Comm&& o) noexcept : comm_(std::exchange(o.comm_, MPI_COMM_NULL)), owned_(o.owned_) {}
  Comm& operator=(Comm&& o) noexcept {
    if (this != &o) {
      reset();
      comm_ = std::exchange(o.comm_, MPI_COMM_NULL);
      owned_ = o.owned_;
    }
    return *this;
  }
  Comm(const Comm&) = delete;
  Comm& operator=(const Comm&) = delete;

  static Comm world() { return Comm(MPI_COMM_WORLD, false); }

  [[nodiscard]] MPI_Comm get() const { return comm_; }
  [[nodiscard]] int rank() const;
  [[nodiscard]] int size() const;
  [[nodiscard]] int remote_size() const;  // intercommunicators only
  [[nodiscard]] bool valid() const { return comm_ != MPI_COMM_NULL; }

 private:
  void reset();
  MPI_Comm comm_ = MPI_COMM_NULL;
  bool owned_ = false;
};

// MPI's blocking calls spin a core while they wait. PBMS runs programs
// oversubscribed (coupler + drivers on few cores), so idle processes poll
// with a sleep between tries instead (mpi::PollingPause).
void wait_gently(MPI_Request& request, MPI_Status* status = MPI_STATUS_IGNORE);
// Broadcast that idles gently while waiting.
void bcast_gently(void* data, int count, MPI_Datatype type, int root, MPI_Comm comm);

// Throws pbms::Error naming the MPI call when `rc` is an error code.
void check(int rc, const char* what);

}  // namespace pbms::mpi
