#include "engine/ghost_exchange.hpp"

#include <cstdint>

#include "pbms/mpi/comm.hpp"

namespace pbms::dpd {

namespace {

constexpr int kGhostWidth = 9;  // id, type, x3, v3, group mask

int rank_or_null(int r) {
  return r < 0 ? MPI_PROC_NULL : r;
}

// Exchanges counts, then doubles, with one partner pair.
std::size_t exchange(MPI_Comm comm, int send_to, int receive_from, const std::vector<double>& out,
                     std::vector<double>& in, int tag) {
  long long n_out = static_cast<long long>(out.size()), n_in = 0;
  mpi::check(MPI_Sendrecv(&n_out, 1, MPI_LONG_LONG, send_to, tag, &n_in, 1, MPI_LONG_LONG,
                          receive_from, tag, comm, MPI_STATUS_IGNORE),
             "MPI_Sendrecv (ghost counts)");
  if (receive_from == MPI_PROC_NULL) n_in = 0;
  in.resize(static_cast<std::size_t>(n_in));
  mpi::check(MPI_Sendrecv(out.data(), static_cast<int>(n_out), MPI_DOUBLE, send_to, tag + 1,
                          in.data(), static_cast<int>(n_in), MPI_DOUBLE, receive_from, tag + 1,
                          comm, MPI_STATUS_IGNORE),
             "MPI_Sendrecv (ghosts)");
  return in.size();
}

}  // namespace

GhostExchange::GhostExchange(const DomainDecomposition& domain, double reach)
    : domain_(domain), reach_(reach) {}

void GhostExchange::build(DpdParticles& particles, std::size_t owned) {
  particles.truncate(owned);
  swaps_.clear();
  const OrthogonalBox& box = domain_.box();
  for (int a = 0; a < 3; ++a) {
    if (!domain_.split(a)) continue;
    // Ghosts received along this axis are not sent back along it.
    const std::size_t candidates = particles.size();
    for (const int direction : {-1, +1}) {
      Swap s;
      s.axis = a;
      s.send_to = rank_or_null(domain_.neighbour(a, direction));
      s.receive_from = rank_or_null(domain_.neighbour(a, -direction));
      const bool at_edge =
          direction < 0 ? domain_.coords()[a] == 0 : domain_.coords()[a] + 1 == domain_.dims()[a];
      if (at_edge && box.periodic[a]) s.shift = -direction * box.length(a);
      if (s.send_to != MPI_PROC_NULL) {
        for (std::size_t i = 0; i < candidates; ++i) {
          const double xa = particles.x[i][a];
          if (direction < 0 ? xa < domain_.sub_lo(a) + reach_ : xa >= domain_.sub_hi(a) - reach_) {
            s.send.push_back(i);
          }
        }
      }
      send_buffer_.clear();
      for (const std::size_t i : s.send) {
        Vec3 x = particles.x[i];
        x[a] += s.shift;
        send_buffer_.insert(
            send_buffer_.end(),
            {static_cast<double>(particles.id[i]), static_cast<double>(particles.type[i]), x[0],
             x[1], x[2], particles.v[i][0], particles.v[i][1], particles.v[i][2],
             static_cast<double>(particles.group_mask[i])});
      }
      exchange(domain_.comm(), s.send_to, s.receive_from, send_buffer_, receive_buffer_,
               100 + 4 * a + (direction + 1));
      s.receive_first = particles.size();
      s.receive_count = receive_buffer_.size() / kGhostWidth;
      for (std::size_t k = 0; k < s.receive_count; ++k) {
        const double* r = &receive_buffer_[k * kGhostWidth];
        particles.add(static_cast<std::int64_t>(r[0]), static_cast<int>(r[1]), {r[2], r[3], r[4]},
                      {r[5], r[6], r[7]});
        particles.group_mask.back() = static_cast<std::uint32_t>(r[8]);
      }
      swaps_.push_back(std::move(s));
    }
  }
  ghosts_ = particles.size() - owned;
}

void GhostExchange::forward(DpdParticles& particles) const {
  for (const Swap& s : swaps_) {
    send_buffer_.clear();
    send_buffer_.reserve(6 * s.send.size());
    for (const std::size_t i : s.send) {
      Vec3 x = particles.x[i];
      x[s.axis] += s.shift;
      send_buffer_.insert(send_buffer_.end(), {x[0], x[1], x[2], particles.v[i][0],
                                               particles.v[i][1], particles.v[i][2]});
    }
    receive_buffer_.resize(6 * s.receive_count);
    mpi::check(MPI_Sendrecv(send_buffer_.data(), static_cast<int>(send_buffer_.size()), MPI_DOUBLE,
                            s.send_to, 200, receive_buffer_.data(),
                            static_cast<int>(receive_buffer_.size()), MPI_DOUBLE, s.receive_from,
                            200, domain_.comm(), MPI_STATUS_IGNORE),
               "MPI_Sendrecv (ghost positions)");
    for (std::size_t k = 0; k < s.receive_count; ++k) {
      const double* r = &receive_buffer_[6 * k];
      particles.x[s.receive_first + k] = {r[0], r[1], r[2]};
      particles.v[s.receive_first + k] = {r[3], r[4], r[5]};
    }
  }
}

void GhostExchange::forward(std::vector<double>& values) const {
  for (const Swap& s : swaps_) {
    send_buffer_.clear();
    for (const std::size_t i : s.send) send_buffer_.push_back(values[i]);
    receive_buffer_.resize(s.receive_count);
    mpi::check(MPI_Sendrecv(send_buffer_.data(), static_cast<int>(send_buffer_.size()), MPI_DOUBLE,
                            s.send_to, 300, receive_buffer_.data(),
                            static_cast<int>(receive_buffer_.size()), MPI_DOUBLE, s.receive_from,
                            300, domain_.comm(), MPI_STATUS_IGNORE),
               "MPI_Sendrecv (ghost values)");
    for (std::size_t k = 0; k < s.receive_count; ++k) {
      values[s.receive_first + k] = receive_buffer_[k];
    }
  }
}

void GhostExchange::reverse(DpdParticles& particles, std::vector<char>& touched,
                            bool internal_energy) const {
  const std::size_t width = internal_energy ? 5 : 4;  // mark, v, u
  for (auto it = swaps_.rbegin(); it != swaps_.rend(); ++it) {
    const Swap& s = *it;
    send_buffer_.clear();
    for (std::size_t k = 0; k < s.receive_count; ++k) {
      const std::size_t g = s.receive_first + k;
      const Vec3& v = particles.v[g];
      send_buffer_.insert(send_buffer_.end(), {touched[g] ? 1.0 : 0.0, v[0], v[1], v[2]});
      if (internal_energy) send_buffer_.push_back(particles.internal_energy[g]);
    }
    receive_buffer_.resize(width * s.send.size());
    mpi::check(MPI_Sendrecv(send_buffer_.data(), static_cast<int>(send_buffer_.size()), MPI_DOUBLE,
                            s.receive_from, 400, receive_buffer_.data(),
                            static_cast<int>(receive_buffer_.size()), MPI_DOUBLE, s.send_to, 400,
                            domain_.comm(), MPI_STATUS_IGNORE),
               "MPI_Sendrecv (ghost velocities back)");
    for (std::size_t k = 0; k < s.send.size(); ++k) {
      const double* r = &receive_buffer_[width * k];
      if (r[0] == 0.0) continue;
      const std::size_t i = s.send[k];
      particles.v[i] = {r[1], r[2], r[3]};
      if (internal_energy) particles.internal_energy[i] = r[4];
      touched[i] = 1;
    }
  }
}

}  // namespace pbms::dpd
