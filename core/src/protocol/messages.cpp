#include "pbms/protocol/messages.hpp"

#include <fmt/format.h>

namespace pbms::protocol {
namespace {

template <typename T>
Message decode_as(Decoder& d) {
  T m;
  d.get(m);
  if (!d.at_end()) {
    throw Error(fmt::format("protocol: trailing bytes after a {} message", type_name(T::kType)));
  }
  return m;
}

}  // namespace

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
    case MessageType::kRegroup:
      return "Regroup";
    case MessageType::kStageFailed:
      return "StageFailed";
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
        e.put(msg);
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
    case MessageType::kRegroup:
      return decode_as<Regroup>(d);
    case MessageType::kStageFailed:
      return decode_as<StageFailed>(d);
  }
  throw Error(fmt::format("protocol: unknown message type {}", static_cast<int>(type)));
}

}  // namespace pbms::protocol
