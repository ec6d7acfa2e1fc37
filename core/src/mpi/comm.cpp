#include "pbms/mpi/comm.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/polling_pause.hpp"

namespace pbms::mpi {

Environment::Environment(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  // Errors come back as codes we turn into messages that name the call,
  // instead of MPI aborting without saying who failed.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

Environment::~Environment() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  // PMPI_: our own, orderly finalize; MPI_Finalize itself may be guarded.
  if (!finalized) PMPI_Finalize();
}

int Comm::rank() const {
  int r = 0;
  MPI_Comm_rank(comm_, &r);
  return r;
}

int Comm::size() const {
  int s = 0;
  MPI_Comm_size(comm_, &s);
  return s;
}

int Comm::remote_size() const {
  int s = 0;
  MPI_Comm_remote_size(comm_, &s);
  return s;
}

void Comm::reset() {
  if (owned_ && comm_ != MPI_COMM_NULL && comm_ != MPI_COMM_WORLD && comm_ != MPI_COMM_SELF) {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Comm_free(&comm_);
  }
  comm_ = MPI_COMM_NULL;
}

void wait_gently(MPI_Request& request, MPI_Status* status) {
  PollingPause pause;
  for (;;) {
    int done = 0;
    check(MPI_Test(&request, &done, status), "MPI_Test");
    if (done) return;
    pause.sleep();
  }
}

void bcast_gently(void* data, int count, MPI_Datatype type, int root, MPI_Comm comm) {
  MPI_Request req;
  check(MPI_Ibcast(data, count, type, root, comm, &req), "MPI_Ibcast");
  wait_gently(req);
}

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw Error(fmt::format("{} failed: {}", what, std::string(text, static_cast<size_t>(len))));
}

}  // namespace pbms::mpi
