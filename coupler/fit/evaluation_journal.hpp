// Every judged candidate of a fit, one line each, appended and flushed as it
// is judged: what a fit killed midway resumes from. NLopt keeps no state of
// its own, so replaying the recorded answers to the same seeded optimiser
// walks the same path, and no candidate is judged twice.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fit/fit_objective.hpp"

namespace pbms::coupler::fit {

struct JournalEntry {
  int phase = 0;
  double temperature = 0.0;
  std::vector<double> params;
  Judgement judgement;
};

class EvaluationJournal {
 public:
  // Opens `file` for appending; with `resume`, first reads what it holds (a
  // line cut short by a kill is dropped), otherwise starts it empty.
  EvaluationJournal(std::filesystem::path file, bool resume);

  // The recorded answer for this candidate if the journal's next entry is
  // exactly it; nothing once the record is used up. Throws pbms::Error if
  // the next entry is another candidate: the fit is not the one recorded.
  std::optional<Judgement> replay(int phase, double temperature, const std::vector<double>& params);
  void record(const JournalEntry& e);

  [[nodiscard]] size_t replayed() const { return replayed_; }
  [[nodiscard]] size_t recorded() const { return entries_.size(); }

 private:
  std::filesystem::path file_;
  std::vector<JournalEntry> entries_;
  size_t next_ = 0;
  size_t replayed_ = 0;
  std::ofstream out_;
};

}  // namespace pbms::coupler::fit
