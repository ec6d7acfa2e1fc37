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
inline constexpr uint16_t kProtocolVersion = 1;

enum class MessageType : uint16_t {
  kHello = 1,      // driver -> coupler: who I am, what I can run
  kWelcome = 2,    // coupler -> driver: accepted or refused, and the peers
  kRunStage = 3,   // coupler -> driver: run one stage
  kProgress = 4,   // driver -> coupler: where a stage is
  kStageDone = 5,  // driver -> coupler: a stage's results
  kFatal = 6,      // any driver rank -> coupler: this rank cannot go on
  kShutdown = 7,   // coupler -> driver: no more work
};

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
  int32_t index = 0;
  std::string name;
  std::string kind;
  std::string params_yaml;     // resolved parameters, references substituted
  std::string materials_yaml;  // the workflow's resolved materials block
  std::string run_dir;
  uint64_t seed = 0;
  PBMS_FIELDS(index, name, kind, params_yaml, materials_yaml, run_dir, seed)
};

struct Progress {
  static constexpr auto kType = MessageType::kProgress;
  std::string stage;
  int64_t step = 0;
  int64_t total_steps = 0;
  double sim_time_ps = 0.0;
  std::string phase;  // "p = 5 GPa, production"
  PBMS_FIELDS(stage, step, total_steps, sim_time_ps, phase)
};

struct StageDone {
  static constexpr auto kType = MessageType::kStageDone;
  std::string stage;
  double wall_s = 0.0;
  StageResults results;
  PBMS_FIELDS(stage, wall_s, results)
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

using Message = std::variant<Hello, Welcome, RunStage, Progress, StageDone, Fatal, Shutdown>;

std::vector<std::byte> pack(const Message& m);
// Throws pbms::Error on a foreign, corrupt or other-version message.
Message unpack(const std::byte* data, size_t size);
std::string_view type_name(MessageType t);

}  // namespace pbms::protocol
