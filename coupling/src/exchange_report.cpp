#include "pbms/coupling/exchange_report.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

constexpr std::array<const char*, 5> kFields = {"messages_sent", "bytes_sent", "bytes_received",
                                                "seconds_packing", "seconds_waiting"};

enum Field : std::size_t {
  kMessagesSent,
  kBytesSent,
  kBytesReceived,
  kSecondsPacking,
  kSecondsWaiting
};

std::array<double, kFields.size()> row_of(const ExchangeProfile& p) {
  return {static_cast<double>(p.messages_sent), static_cast<double>(p.bytes_sent),
          static_cast<double>(p.bytes_received), p.seconds_packing, p.seconds_waiting};
}

}  // namespace

void report_exchanges(StageResults& r, MPI_Comm comm, const std::string& prefix,
                      const ExchangeProfile& nodal, const ExchangeProfile& partners,
                      std::int64_t steps, double stepping_seconds) {
  constexpr int kWidth = 2 * static_cast<int>(kFields.size());
  std::vector<double> mine;
  for (const auto& p : {nodal, partners}) {
    const auto row = row_of(p);
    mine.insert(mine.end(), row.begin(), row.end());
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<double> all(rank == 0 ? static_cast<std::size_t>(size * kWidth) : 0);
  mpi::check(MPI_Gather(mine.data(), kWidth, MPI_DOUBLE, all.data(), kWidth, MPI_DOUBLE, 0, comm),
             "MPI_Gather (exchange profile)");
  if (rank != 0) return;

  const std::string table = prefix + "_exchange";
  std::vector<double> ranks(static_cast<std::size_t>(size));
  for (int k = 0; k < size; ++k) ranks[static_cast<std::size_t>(k)] = k;
  r.add_column(table, "rank", "1", ranks);
  for (std::size_t kind = 0; kind < 2; ++kind) {
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      std::vector<double> column;
      for (int k = 0; k < size; ++k) {
        column.push_back(all[static_cast<std::size_t>(k * kWidth) + kind * kFields.size() + f]);
      }
      const std::string field = kFields[f];
      const std::string unit = field.starts_with("seconds") ? "s" : "1";
      r.add_column(table, (kind == 0 ? "nodal_" : "partner_") + field, unit, column);
    }
  }
  double bytes = 0.0, messages = 0.0, most_waiting = 0.0;
  for (int k = 0; k < size; ++k) {
    double waiting = 0.0;
    for (std::size_t kind = 0; kind < 2; ++kind) {
      const double* f = &all[static_cast<std::size_t>(k * kWidth) + kind * kFields.size()];
      messages += f[kMessagesSent];
      bytes += f[kBytesSent] + f[kBytesReceived];
      waiting += f[kSecondsWaiting];
    }
    most_waiting = std::max(most_waiting, waiting);
  }
  const double n = static_cast<double>(std::max<std::int64_t>(steps, 1));
  r.add_scalar(prefix + "_exchange_bytes_per_step", bytes / n, "1");
  r.add_scalar(prefix + "_exchange_messages_per_step", messages / n, "1");
  if (stepping_seconds > 0.0) {
    r.add_scalar(prefix + "_exchange_waiting_fraction", most_waiting / stepping_seconds, "1");
  }
}

}  // namespace pbms::coupling
