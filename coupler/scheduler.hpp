// The coupler's view of its drivers: a pool of links, each driver split into
// rank groups, and the requests queued or in flight on them. A coupler-side
// stage (a fit, a sweep) submits many requests and reads their answers as
// they come; a workflow stage is one request on an unsplit driver. The
// scheduler only moves control messages: driver-to-driver data never passes
// through it.
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "pbms/mpi/mpmd.hpp"
#include "pbms/protocol/messages.hpp"

namespace pbms::coupler {

struct DriverLink {
  mpi::App app;
  mpi::Channel channel;
  protocol::Hello hello;
};

// What a request answers besides its progress: a result or a failure that
// left the driver in service.
using Answer = std::variant<protocol::Progress, protocol::StageDone, protocol::StageFailed>;

[[nodiscard]] protocol::RequestId request_of(const Answer& a);

class Scheduler {
 public:
  // Called for a Fatal from any driver rank; must not return (the job ends).
  using FatalHandler = std::function<void(const protocol::Fatal&)>;

  Scheduler() = default;
  Scheduler(std::vector<DriverLink> links, FatalHandler on_fatal);

  // Opens a link to every driver of the job and reads its Hello. Collective
  // over MPI_COMM_WORLD (it builds the intercommunicators).
  static std::vector<DriverLink> connect(const mpi::MpmdWorld& world);

  [[nodiscard]] const std::vector<DriverLink>& links() const { return links_; }
  [[nodiscard]] const DriverLink& link(const std::string& program) const;

  // Splits `program` into groups of `group_ranks` consecutive ranks (the last
  // one may be smaller); group_ranks >= the driver's size makes one group.
  // The driver must be idle: nothing queued or in flight on it.
  void regroup(const std::string& program, int group_ranks);
  [[nodiscard]] int groups(const std::string& program) const;

  // Queues a request for `program`; it starts as soon as one of the driver's
  // groups is free, in the order of submission. Returns its id, also written
  // into the request.
  protocol::RequestId submit(const std::string& program, protocol::RunStage request);

  // The next answer of any request, or nothing if none came within
  // `timeout`. Progress answers leave the request in flight; StageDone and
  // StageFailed end it and free its group for the next queued request.
  std::optional<Answer> next(std::chrono::milliseconds timeout);
  // Waits for answers until `request` is done or failed, handing every other
  // answer (and this request's progress) to `other`.
  Answer wait_for(protocol::RequestId request, const std::function<void(const Answer&)>& other);

  // Requests not yet answered with StageDone or StageFailed.
  [[nodiscard]] size_t unfinished() const;
  [[nodiscard]] size_t unfinished(const std::string& program) const;
  // Requests of `program` that a group is working on now.
  [[nodiscard]] size_t running(const std::string& program) const;

  // Sends Shutdown to every group leader of every driver.
  void shutdown(const std::string& reason);
  // Refuses every driver (at the handshake): Welcome with accepted = false.
  void welcome(bool accepted, const std::string& reason) const;

 private:
  struct Pool {
    int group_ranks = 0;
    std::vector<int> leaders;  // program-local rank of each group's rank 0
    std::vector<int> idle;     // leaders with nothing in flight
    std::deque<protocol::RunStage> queue;
    std::map<protocol::RequestId, int> in_flight;  // request -> leader
  };

  size_t index_of(const std::string& program) const;
  void dispatch(size_t link);
  std::optional<Answer> poll_once();
  Answer accept(size_t link, protocol::Message message, int source);

  std::vector<DriverLink> links_;
  std::vector<Pool> pools_;
  FatalHandler on_fatal_;
  protocol::RequestId next_id_ = 1;
};

}  // namespace pbms::coupler
