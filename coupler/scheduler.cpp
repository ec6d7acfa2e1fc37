#include "scheduler.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/polling_pause.hpp"

namespace pbms::coupler {

using Clock = std::chrono::steady_clock;

protocol::RequestId request_of(const Answer& a) {
  return std::visit([](const auto& m) { return m.request; }, a);
}

Scheduler::Scheduler(std::vector<DriverLink> links, FatalHandler on_fatal)
    : links_(std::move(links)), pools_(links_.size()), on_fatal_(std::move(on_fatal)) {
  for (auto& pool : pools_) pool.leaders = pool.idle = {0};
  for (size_t i = 0; i < links_.size(); ++i) pools_[i].group_ranks = links_[i].app.size;
}

std::vector<DriverLink> Scheduler::connect(const mpi::MpmdWorld& world) {
  std::vector<DriverLink> links;
  for (const auto& app : world.drivers()) {
    links.push_back({app, mpi::Channel(world.connect(app)), {}});
  }
  for (auto& l : links) {
    auto m = l.channel.receive();
    auto* h = std::get_if<protocol::Hello>(&m);
    if (!h) throw Error("a driver opened with something other than Hello");
    l.hello = *h;
  }
  return links;
}

size_t Scheduler::index_of(const std::string& program) const {
  for (size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].hello.program == program) return i;
  }
  throw Error(fmt::format("{} is not part of this job", program));
}

const DriverLink& Scheduler::link(const std::string& program) const {
  return links_[index_of(program)];
}

void Scheduler::welcome(bool accepted, const std::string& reason) const {
  for (const auto& l : links_) {
    protocol::Welcome w;
    w.accepted = accepted;
    w.reason = reason;
    for (const auto& o : links_) {
      if (o.app.appnum != l.app.appnum) {
        w.peers.push_back({o.hello.program, o.app.appnum, o.app.size});
      }
    }
    l.channel.send(w, 0);
  }
}

void Scheduler::regroup(const std::string& program, int group_ranks) {
  const size_t i = index_of(program);
  Pool& pool = pools_[i];
  if (!pool.queue.empty() || !pool.in_flight.empty()) {
    throw Error(fmt::format("cannot regroup {} while it has requests queued or running", program));
  }
  const int size = links_[i].app.size;
  const int n = std::clamp(group_ranks, 1, size);
  if (n == pool.group_ranks) return;
  for (const int leader : pool.leaders) links_[i].channel.send(protocol::Regroup{n}, leader);
  pool.group_ranks = n;
  pool.leaders.clear();
  for (int r = 0; r < size; r += n) pool.leaders.push_back(r);
  pool.idle = pool.leaders;
}

int Scheduler::groups(const std::string& program) const {
  return static_cast<int>(pools_[index_of(program)].leaders.size());
}

protocol::RequestId Scheduler::submit(const std::string& program, protocol::RunStage request) {
  const size_t i = index_of(program);
  const protocol::RequestId id = next_id_++;
  request.request = id;
  pools_[i].queue.push_back(std::move(request));
  dispatch(i);
  return id;
}

// Lowest free leader first, so that the same submissions land on the same
// groups in every run.
void Scheduler::dispatch(size_t i) {
  Pool& pool = pools_[i];
  std::sort(pool.idle.begin(), pool.idle.end(), std::greater<>());
  while (!pool.queue.empty() && !pool.idle.empty()) {
    const int leader = pool.idle.back();
    pool.idle.pop_back();
    const protocol::RunStage& rs = pool.queue.front();
    links_[i].channel.send(rs, leader);
    pool.in_flight[rs.request] = leader;
    pool.queue.pop_front();
  }
}

Answer Scheduler::accept(size_t i, protocol::Message message, int source) {
  const std::string& program = links_[i].hello.program;
  if (const auto* f = std::get_if<protocol::Fatal>(&message)) {
    if (on_fatal_) on_fatal_(*f);
    throw Error(fmt::format("{} rank {} failed: {}", f->program, f->rank, f->message));
  }
  const auto type = std::visit([](const auto& m) { return m.kType; }, message);
  Answer answer;
  if (auto* p = std::get_if<protocol::Progress>(&message)) {
    answer = std::move(*p);
  } else if (auto* d = std::get_if<protocol::StageDone>(&message)) {
    answer = std::move(*d);
  } else if (auto* s = std::get_if<protocol::StageFailed>(&message)) {
    answer = std::move(*s);
  } else {
    throw Error(fmt::format("protocol error: {} rank {} sent an unexpected {} message", program,
                            source, protocol::type_name(type)));
  }
  Pool& pool = pools_[i];
  const auto it = pool.in_flight.find(request_of(answer));
  if (it == pool.in_flight.end() || it->second != source) {
    throw Error(fmt::format("protocol error: {} rank {} answered request {}, which it was not sent",
                            program, source, request_of(answer)));
  }
  if (!std::holds_alternative<protocol::Progress>(answer)) {
    pool.idle.push_back(it->second);
    pool.in_flight.erase(it);
    dispatch(i);
  }
  return answer;
}

std::optional<Answer> Scheduler::poll_once() {
  for (size_t i = 0; i < links_.size(); ++i) {
    int source = 0;
    auto m = links_[i].channel.poll(&source);
    if (m) return accept(i, std::move(*m), source);
  }
  return std::nullopt;
}

// Polls with mpi::PollingPause between tries: the coupler shares cores with
// the drivers and must not spin.
std::optional<Answer> Scheduler::next(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  mpi::PollingPause pause;
  for (;;) {
    if (auto a = poll_once()) return a;
    if (Clock::now() >= deadline) return std::nullopt;
    pause.sleep();
  }
}

Answer Scheduler::wait_for(protocol::RequestId request,
                           const std::function<void(const Answer&)>& other) {
  for (;;) {
    auto a = next(std::chrono::milliseconds(500));
    if (!a) continue;
    if (request_of(*a) == request && !std::holds_alternative<protocol::Progress>(*a)) return *a;
    if (other) other(*a);
  }
}

size_t Scheduler::unfinished() const {
  size_t n = 0;
  for (const auto& pool : pools_) n += pool.queue.size() + pool.in_flight.size();
  return n;
}

size_t Scheduler::unfinished(const std::string& program) const {
  const Pool& pool = pools_[index_of(program)];
  return pool.queue.size() + pool.in_flight.size();
}

size_t Scheduler::running(const std::string& program) const {
  return pools_[index_of(program)].in_flight.size();
}

void Scheduler::shutdown(const std::string& reason) {
  for (size_t i = 0; i < links_.size(); ++i) {
    for (const int leader : pools_[i].leaders) {
      links_[i].channel.send(protocol::Shutdown{reason}, leader);
    }
  }
}

}  // namespace pbms::coupler
