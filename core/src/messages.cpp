#include "pbms/protocol/messages.hpp"

#include <fmt/format.h>

namespace pbms::protocol {
namespace {

void encode_results(Encoder& e, const StageResults& r) {
  e.put<uint64_t>(r.scalars.size());
  for (const auto& s : r.scalars) {
    e.put(s.key);
    e.put(s.value);
    e.put(s.unit);
    e.put(s.std_error);
  }
  e.put<uint64_t>(r.columns.size());
  for (const auto& c : r.columns) {
    e.put(c.table);
    e.put(c.name);
    e.put(c.unit);
    e.put(c.data);
  }
  e.put(r.files);
  e.put<uint64_t>(r.attributes.size());
  for (const auto& [k, v] : r.attributes) {
    e.put(k);
    e.put(v);
  }
}

StageResults decode_results(Decoder& d) {
  StageResults r;
  const auto ns = d.get<uint64_t>();
  for (uint64_t i = 0; i < ns; ++i) {
    ScalarResult s;
    d.get(s.key);
    d.get(s.value);
    d.get(s.unit);
    d.get(s.std_error);
    r.scalars.push_back(std::move(s));
  }
  const auto nc = d.get<uint64_t>();
  for (uint64_t i = 0; i < nc; ++i) {
    Column c;
    d.get(c.table);
    d.get(c.name);
    d.get(c.unit);
    d.get(c.data);
    r.columns.push_back(std::move(c));
  }
  d.get(r.files);
  const auto na = d.get<uint64_t>();
  for (uint64_t i = 0; i < na; ++i) {
    std::string k, v;
    d.get(k);
    d.get(v);
    r.attributes[k] = v;
  }
  return r;
}

template <typename T>
Message decode_as(Decoder& d) {
  T m = T::decode(d);
  if (!d.at_end())
    throw Error(fmt::format("protocol: trailing bytes after a {} message", type_name(T::kType)));
  return m;
}

}  // namespace

void Hello::encode(Encoder& e) const {
  e.put(program);
  e.put(short_name);
  e.put(protocol_version);
  e.put(ranks);
  e.put(capabilities);
  e.put(software);
}
Hello Hello::decode(Decoder& d) {
  Hello m;
  d.get(m.program);
  d.get(m.short_name);
  d.get(m.protocol_version);
  d.get(m.ranks);
  d.get(m.capabilities);
  d.get(m.software);
  return m;
}

void Welcome::encode(Encoder& e) const {
  e.put<uint8_t>(accepted ? 1 : 0);
  e.put(reason);
  e.put<uint64_t>(peers.size());
  for (const auto& p : peers) {
    e.put(p.program);
    e.put(p.app);
    e.put(p.ranks);
  }
}
Welcome Welcome::decode(Decoder& d) {
  Welcome m;
  m.accepted = d.get<uint8_t>() != 0;
  d.get(m.reason);
  const auto n = d.get<uint64_t>();
  for (uint64_t i = 0; i < n; ++i) {
    Peer p;
    d.get(p.program);
    d.get(p.app);
    d.get(p.ranks);
    m.peers.push_back(std::move(p));
  }
  return m;
}

void RunStage::encode(Encoder& e) const {
  e.put(index);
  e.put(name);
  e.put(kind);
  e.put(params_yaml);
  e.put(materials_yaml);
  e.put(run_dir);
  e.put(seed);
}
RunStage RunStage::decode(Decoder& d) {
  RunStage m;
  d.get(m.index);
  d.get(m.name);
  d.get(m.kind);
  d.get(m.params_yaml);
  d.get(m.materials_yaml);
  d.get(m.run_dir);
  d.get(m.seed);
  return m;
}

void Progress::encode(Encoder& e) const {
  e.put(stage);
  e.put(step);
  e.put(total_steps);
  e.put(sim_time_ps);
  e.put(phase);
}
Progress Progress::decode(Decoder& d) {
  Progress m;
  d.get(m.stage);
  d.get(m.step);
  d.get(m.total_steps);
  d.get(m.sim_time_ps);
  d.get(m.phase);
  return m;
}

void StageDone::encode(Encoder& e) const {
  e.put(stage);
  e.put(wall_s);
  encode_results(e, results);
}
StageDone StageDone::decode(Decoder& d) {
  StageDone m;
  d.get(m.stage);
  d.get(m.wall_s);
  m.results = decode_results(d);
  return m;
}

void Fatal::encode(Encoder& e) const {
  e.put(program);
  e.put(rank);
  e.put(stage);
  e.put(step);
  e.put(message);
}
Fatal Fatal::decode(Decoder& d) {
  Fatal m;
  d.get(m.program);
  d.get(m.rank);
  d.get(m.stage);
  d.get(m.step);
  d.get(m.message);
  return m;
}

void Shutdown::encode(Encoder& e) const {
  e.put(reason);
}
Shutdown Shutdown::decode(Decoder& d) {
  Shutdown m;
  d.get(m.reason);
  return m;
}

std::string_view type_name(MessageType t) {
  switch (t) {
    case MessageType::kHello:
      return "Hello";
    case MessageType::kWelcome:
      return "Welcome";
    case MessageType::kRunStage:
      return "RunStage";
    case MessageType::kProgress:
      return "Progress";
    case MessageType::kStageDone:
      return "StageDone";
    case MessageType::kFatal:
      return "Fatal";
    case MessageType::kShutdown:
      return "Shutdown";
  }
  return "unknown";
}

std::vector<std::byte> pack(const Message& m) {
  Encoder e;
  e.put(kMagic);
  e.put(kProtocolVersion);
  std::visit(
      [&](const auto& msg) {
        e.put(static_cast<uint16_t>(std::decay_t<decltype(msg)>::kType));
        msg.encode(e);
      },
      m);
  return e.take();
}

Message unpack(const std::byte* data, size_t size) {
  Decoder d(data, size);
  if (d.get<uint32_t>() != kMagic) throw Error("protocol: message without the PBMS magic number");
  const auto version = d.get<uint16_t>();
  if (version != kProtocolVersion) {
    throw Error(
        fmt::format("protocol: peer speaks version {}, this program speaks version {}; "
                    "rebuild all PBMS programs from one source tree",
                    version, kProtocolVersion));
  }
  const auto type = static_cast<MessageType>(d.get<uint16_t>());
  switch (type) {
    case MessageType::kHello:
      return decode_as<Hello>(d);
    case MessageType::kWelcome:
      return decode_as<Welcome>(d);
    case MessageType::kRunStage:
      return decode_as<RunStage>(d);
    case MessageType::kProgress:
      return decode_as<Progress>(d);
    case MessageType::kStageDone:
      return decode_as<StageDone>(d);
    case MessageType::kFatal:
      return decode_as<Fatal>(d);
    case MessageType::kShutdown:
      return decode_as<Shutdown>(d);
  }
  throw Error(fmt::format("protocol: unknown message type {}", static_cast<int>(type)));
}

}  // namespace pbms::protocol
