// Typed coupler <-> driver messages. Every message travels in an envelope
// (magic, protocol version, type) so that a peer built from another version
// is refused with a clear message instead of misreading bytes.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "pbms/protocol/wire.hpp"
#include "pbms/results.hpp"

namespace pbms::protocol {

inline constexpr uint32_t kMagic = 0x534d4250;  // "PBMS"
inline constexpr uint16_t kProtocolVersion = 3;

enum class MessageType : uint16_t {
  kHello = 1,        // driver -> coupler: who I am, what I can run
  kWelcome = 2,      // coupler -> driver: accepted or refused, and the peers
  kRunStage = 3,     // coupler -> driver: run one stage
  kProgress = 4,     // driver -> coupler: where a stage is
  kStageDone = 5,    // driver -> coupler: a stage's results
  kFatal = 6,        // any driver rank -> coupler: this rank cannot go on
  kShutdown = 7,     // coupler -> driver: no more work
  kRegroup = 8,      // coupler -> every group leader: split the driver into rank groups
  kStageFailed = 9,  // group leader -> coupler: this request has no result; the driver goes on
};

// Every RunStage carries a request id chosen by the coupler, unique within a
// job; the answers (Progress, StageDone, StageFailed) carry it back, so that
// several requests can be in flight on one driver at once.
using RequestId = int64_t;

struct Hello {
  static constexpr auto kType = MessageType::kHello;
  std::string program;
  std::string short_name;
  uint16_t protocol_version = kProtocolVersion;
  int32_t ranks = 0;
  std::vector<std::string> capabilities;  // stage kinds
  std::vector<std::string> software;      // "name=version"
  PBMS_FIELDS(program, short_name, protocol_version, ranks, capabilities, software)
};

struct Peer {
  std::string program;
  int32_t app = 0;  // MPI_APPNUM of the peer's processes
  int32_t ranks = 0;
  PBMS_FIELDS(program, app, ranks)
};

struct Welcome {
  static constexpr auto kType = MessageType::kWelcome;
  bool accepted = false;
  std::string reason;
  std::vector<Peer> peers;
  PBMS_FIELDS(accepted, reason, peers)
};

struct RunStage {
  static constexpr auto kType = MessageType::kRunStage;
  int32_t index = 0;  // of the workflow stage this request serves
  RequestId request = 0;
  std::string name;
  std::string kind;
  std::string params_yaml;     // resolved parameters, references substituted
  std::string materials_yaml;  // the workflow's resolved materials block
  std::string run_dir;
  uint64_t seed = 0;
  std::string checkpoint_yaml;  // the workflow's `checkpoint:` map, resolved; empty: none
  std::string resume_from;      // a checkpoint file of this stage to go on from; empty: start
  PBMS_FIELDS(index, request, name, kind, params_yaml, materials_yaml, run_dir, seed,
              checkpoint_yaml, resume_from)
};

struct Progress {
  static constexpr auto kType = MessageType::kProgress;
  RequestId request = 0;
  std::string stage;
  int64_t step = 0;
  int64_t total_steps = 0;
  double sim_time_ps = 0.0;
  std::string phase;  // "p = 5 GPa, production"
  // Set once a checkpoint after `step` is complete on disk: its file,
  // relative to the run directory. The coupler records it, then prunes.
  std::string checkpoint;
  PBMS_FIELDS(request, stage, step, total_steps, sim_time_ps, phase, checkpoint)
};

struct StageDone {
  static constexpr auto kType = MessageType::kStageDone;
  RequestId request = 0;
  std::string stage;
  double wall_s = 0.0;
  StageResults results;
  PBMS_FIELDS(request, stage, wall_s, results)
};

// A request that could not produce a result (a candidate crystal that melts,
// a NaN), reported by the whole rank group at once. The driver stays in
// service; whether the job goes on is the coupler's decision.
struct StageFailed {
  static constexpr auto kType = MessageType::kStageFailed;
  RequestId request = 0;
  std::string stage;
  std::string program;
  int32_t rank = 0;   // the group leader's rank in its program
  int64_t step = -1;  // -1 when not inside a time loop
  double wall_s = 0.0;
  std::string reason;
  PBMS_FIELDS(request, stage, program, rank, step, wall_s, reason)
};

struct Fatal {
  static constexpr auto kType = MessageType::kFatal;
  std::string program;
  int32_t rank = 0;
  std::string stage;  // empty outside a stage
  int64_t step = -1;  // -1 when not inside a time loop
  std::string message;
  PBMS_FIELDS(program, rank, stage, step, message)
};

struct Shutdown {
  static constexpr auto kType = MessageType::kShutdown;
  std::string reason;
  PBMS_FIELDS(reason)
};

// Splits a driver's ranks into groups of `group_ranks` consecutive ranks
// (the last group may be smaller); each group then serves one request at a
// time. Sent to every current group leader while the driver is idle.
struct Regroup {
  static constexpr auto kType = MessageType::kRegroup;
  int32_t group_ranks = 0;
  PBMS_FIELDS(group_ranks)
};

using Message = std::variant<Hello, Welcome, RunStage, Progress, StageDone, Fatal, Shutdown,
                             Regroup, StageFailed>;

std::vector<std::byte> pack(const Message& m);
// Throws pbms::Error on a foreign, corrupt or other-version message.
Message unpack(const std::byte* data, size_t size);
std::string_view type_name(MessageType t);

}  // namespace pbms::protocol
