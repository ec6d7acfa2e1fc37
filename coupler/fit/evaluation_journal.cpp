#include "fit/evaluation_journal.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "pbms/error.hpp"

namespace pbms::coupler::fit {
namespace {

void put_optional(YAML::Emitter& e, const char* key, const std::optional<double>& v) {
  if (v) e << YAML::Key << key << YAML::Value << *v;
}

std::optional<double> get_optional(const YAML::Node& n, const char* key) {
  if (!n[key]) return std::nullopt;
  return n[key].as<double>();
}

// One flow map on one line; 17 digits bring every double back exactly.
std::string line_of(const JournalEntry& e) {
  const Judgement& j = e.judgement;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "phase" << YAML::Value << e.phase;
  out << YAML::Key << "temperature" << YAML::Value << e.temperature;
  out << YAML::Key << "params" << YAML::Value << YAML::Flow << e.params;
  out << YAML::Key << "ok" << YAML::Value << j.ok;
  out << YAML::Key << "reason" << YAML::Value << YAML::DoubleQuoted << j.reason;
  out << YAML::Key << "volume" << YAML::Value << YAML::Flow << j.volume_per_atom;
  out << YAML::Key << "pressure_error" << YAML::Value << YAML::Flow << j.pressure_error;
  put_optional(out, "c11", j.c11);
  put_optional(out, "c12", j.c12);
  put_optional(out, "c44", j.c44);
  put_optional(out, "c11_error", j.c11_error);
  put_optional(out, "c12_error", j.c12_error);
  put_optional(out, "c44_error", j.c44_error);
  put_optional(out, "surface_energy_100", j.surface_energy_100);
  out << YAML::Key << "wall_s" << YAML::Value << j.wall_s;
  out << YAML::EndMap;
  return out.c_str();
}

JournalEntry entry_from_yaml(const YAML::Node& n) {
  JournalEntry e;
  e.phase = n["phase"].as<int>();
  e.temperature = n["temperature"].as<double>();
  e.params = n["params"].as<std::vector<double>>();
  Judgement& j = e.judgement;
  j.ok = n["ok"].as<bool>();
  j.reason = n["reason"].as<std::string>();
  j.volume_per_atom = n["volume"].as<std::vector<double>>();
  j.pressure_error = n["pressure_error"].as<std::vector<double>>();
  j.c11 = get_optional(n, "c11");
  j.c12 = get_optional(n, "c12");
  j.c44 = get_optional(n, "c44");
  j.c11_error = get_optional(n, "c11_error");
  j.c12_error = get_optional(n, "c12_error");
  j.c44_error = get_optional(n, "c44_error");
  j.surface_energy_100 = get_optional(n, "surface_energy_100");
  j.wall_s = n["wall_s"].as<double>();
  return e;
}

}  // namespace

EvaluationJournal::EvaluationJournal(std::filesystem::path file, bool resume)
    : file_(std::move(file)) {
  if (resume) {
    std::ifstream in(file_);
    std::string line;
    while (std::getline(in, line)) {
      try {
        entries_.push_back(entry_from_yaml(YAML::Load(line)));
      } catch (const YAML::Exception&) {
        break;  // cut short by the kill that ended the earlier run
      }
    }
  }
  // Rewrite what was read, so that a dropped partial line does not stay.
  out_.open(file_, std::ios::trunc);
  for (const auto& e : entries_) out_ << line_of(e) << "\n";
  out_.flush();
  if (!out_) throw Error(fmt::format("cannot write {}", file_.string()));
}

std::optional<Judgement> EvaluationJournal::replay(int phase, double temperature,
                                                   const std::vector<double>& params) {
  if (next_ >= entries_.size()) return std::nullopt;
  const JournalEntry& e = entries_[next_];
  if (e.phase != phase || e.temperature != temperature || e.params != params) {
    throw Error(fmt::format(
        "{}: recorded evaluation {} is another candidate than the optimiser asks for now: this "
        "is not the fit that was recorded (changed config or seed). Start a new run instead "
        "of --resume",
        file_.string(), next_ + 1));
  }
  ++next_;
  ++replayed_;
  return e.judgement;
}

void EvaluationJournal::record(const JournalEntry& e) {
  entries_.push_back(e);
  next_ = entries_.size();
  out_ << line_of(e) << "\n";
  out_.flush();
  if (!out_) throw Error(fmt::format("cannot write {}", file_.string()));
}

}  // namespace pbms::coupler::fit
