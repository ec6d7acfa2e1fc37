#include "pbms/coupling/point_ghosts_across_programs.hpp"

#include <cmath>

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

constexpr int kGhostTag = 400;
constexpr int kForceTag = 401;
constexpr std::size_t kRecord = 8;  // id, x, v, mass

// Distance from x to the box along one axis (0 inside).
double gap(double x, double lo, double hi) {
  if (x < lo) return lo - x;
  if (x > hi) return x - hi;
  return 0.0;
}

}  // namespace

PointGhostsAcrossPrograms::PointGhostsAcrossPrograms(MPI_Comm inter, Side side, const SpaceBox& box,
                                                     double reach, const PeriodicLengths& periodic)
    : inter_(inter), side_(side), reach_(reach) {
  update_boxes(box, periodic);
}

void PointGhostsAcrossPrograms::update_boxes(const SpaceBox& box, const PeriodicLengths& periodic) {
  box_ = box;
  periodic_ = periodic;
  int remote = 0;
  mpi::check(MPI_Comm_remote_size(inter_, &remote), "MPI_Comm_remote_size");
  // On an intercommunicator every rank receives the remote group's boxes.
  const std::array<double, 9> mine{box.lo[0],          box.lo[1],          box.lo[2],
                                   box.hi[0],          box.hi[1],          box.hi[2],
                                   periodic.length[0], periodic.length[1], periodic.length[2]};
  std::vector<double> theirs(9 * static_cast<std::size_t>(remote));
  mpi::check(MPI_Allgather(mine.data(), 9, MPI_DOUBLE, theirs.data(), 9, MPI_DOUBLE, inter_),
             "MPI_Allgather (ghost boxes across programs)");
  remote_boxes_.clear();
  remote_images_.clear();
  peers_.clear();
  for (int r = 0; r < remote; ++r) {
    const double* b = theirs.data() + 9 * static_cast<std::size_t>(r);
    remote_boxes_.push_back({{b[0], b[1], b[2]}, {b[3], b[4], b[5]}});
    remote_images_.push_back({{b[6], b[7], b[8]}});
  }
  for (int r = 0; r < remote; ++r) {
    const auto rr = static_cast<std::size_t>(r);
    const auto shifts = side_ == Side::kSender ? images(box, remote_boxes_[rr], remote_images_[rr])
                                               : images(remote_boxes_[rr], box, periodic_);
    if (!shifts.empty()) peers_.push_back(r);
  }
  send_buf_.resize(peers_.size());
  sent_from_.resize(peers_.size());
  sent_shift_.resize(peers_.size());
}

std::vector<std::array<int, 3>> PointGhostsAcrossPrograms::images(
    const SpaceBox& from, const SpaceBox& to, const PeriodicLengths& periodic) const {
  std::vector<std::array<int, 3>> out;
  for (int sz = -1; sz <= 1; ++sz) {
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        const std::array<int, 3> s{sx, sy, sz};
        bool ok = true;
        for (std::size_t a = 0; a < 3 && ok; ++a) {
          const double l = periodic.length[a];
          if (s[a] != 0 && l <= 0.0) {
            ok = false;
            continue;
          }
          // The shifted sender box [lo, hi) against the receiver's, grown.
          const double lo = from.lo[a] + s[a] * l, hi = from.hi[a] + s[a] * l;
          ok = lo <= to.hi[a] + reach_ && hi >= to.lo[a] - reach_;
        }
        if (ok) out.push_back(s);
      }
    }
  }
  return out;
}

// Every image of one point within reach of `to`, one pass over the axes
// (at most two images per periodic axis qualify).
int PointGhostsAcrossPrograms::append_images(std::int64_t id, const Vec3& x, const Vec3& v,
                                             double mass, std::size_t p, std::vector<double>& buf,
                                             std::vector<Vec3>& shifts) const {
  const auto peer = static_cast<std::size_t>(peers_[p]);
  const SpaceBox& to = remote_boxes_[peer];
  const PeriodicLengths& periodic = remote_images_[peer];
  std::array<std::array<double, 3>, 3> at{};  // per axis: the qualifying coordinates
  std::array<int, 3> count{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double l = periodic.length[a];
    for (int s = -1; s <= 1; ++s) {
      if (s != 0 && l <= 0.0) continue;
      const double xa = x[a] + s * l;
      if (gap(xa, to.lo[a], to.hi[a]) <= reach_) at[a][static_cast<std::size_t>(count[a]++)] = xa;
    }
    if (count[a] == 0) return 0;
  }
  for (int k = 0; k < count[2]; ++k)
    for (int j = 0; j < count[1]; ++j)
      for (int i = 0; i < count[0]; ++i) {
        const Vec3 at_image{at[0][static_cast<std::size_t>(i)], at[1][static_cast<std::size_t>(j)],
                            at[2][static_cast<std::size_t>(k)]};
        buf.insert(buf.end(), {static_cast<double>(id), at_image[0], at_image[1], at_image[2], v[0],
                               v[1], v[2], mass});
        shifts.push_back({at_image[0] - x[0], at_image[1] - x[1], at_image[2] - x[2]});
      }
  return count[0] * count[1] * count[2];
}

void PointGhostsAcrossPrograms::send(const std::vector<std::int64_t>& id,
                                     const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                                     const std::vector<double>& mass) {
  const double start = MPI_Wtime();
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    auto& buf = send_buf_[p];
    auto& from = sent_from_[p];
    buf.clear();
    from.clear();
    sent_shift_[p].clear();
    for (std::size_t i = 0; i < id.size(); ++i) {
      const int n = append_images(id[i], x[i], v[i], mass[i], p, buf, sent_shift_[p]);
      from.insert(from.end(), static_cast<std::size_t>(n), i);
    }
  }
  profile_.seconds_packing += MPI_Wtime() - start;
  post_sends();
}

void PointGhostsAcrossPrograms::resend(const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
  const double start = MPI_Wtime();
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    auto& buf = send_buf_[p];
    const auto& from = sent_from_[p];
    for (std::size_t k = 0; k < from.size(); ++k) {
      double* r = buf.data() + k * kRecord;
      for (std::size_t a = 0; a < 3; ++a) {
        r[1 + a] = x[from[k]][a] + sent_shift_[p][k][a];
        r[4 + a] = v[from[k]][a];
      }
    }
  }
  profile_.seconds_packing += MPI_Wtime() - start;
  post_sends();
}

void PointGhostsAcrossPrograms::post_sends() {
  const double start = MPI_Wtime();
  requests_.assign(peers_.size(), MPI_REQUEST_NULL);
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    const auto& buf = send_buf_[p];
    mpi::check(MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, peers_[p], kGhostTag,
                         inter_, &requests_[p]),
               "MPI_Isend (ghosts across programs)");
    profile_.bytes_sent += static_cast<std::int64_t>(buf.size() * sizeof(double));
  }
  profile_.messages_sent += static_cast<std::int64_t>(peers_.size());
  const double posted = MPI_Wtime();
  mpi::check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
             "MPI_Waitall (ghosts across programs)");
  ++profile_.exchanges;
  profile_.seconds_packing += posted - start;
  profile_.seconds_waiting += MPI_Wtime() - posted;
}

const std::vector<GhostPoint>& PointGhostsAcrossPrograms::receive() {
  ghosts_.clear();
  received_.clear();
  double waiting = 0.0;
  const double start = MPI_Wtime();
  for (const int peer : peers_) {
    const double before = MPI_Wtime();
    MPI_Message message = MPI_MESSAGE_NULL;
    MPI_Status status;
    mpi::check(MPI_Mprobe(peer, kGhostTag, inter_, &message, &status),
               "MPI_Mprobe (ghosts across programs)");
    int count = 0;
    mpi::check(MPI_Get_count(&status, MPI_DOUBLE, &count), "MPI_Get_count");
    recv_buf_.resize(static_cast<std::size_t>(count));
    mpi::check(MPI_Mrecv(recv_buf_.data(), count, MPI_DOUBLE, &message, MPI_STATUS_IGNORE),
               "MPI_Mrecv (ghosts across programs)");
    waiting += MPI_Wtime() - before;
    profile_.bytes_received += static_cast<std::int64_t>(count) * 8;
    received_.push_back(static_cast<std::size_t>(count) / kRecord);
    for (std::size_t r = 0; r + kRecord <= recv_buf_.size(); r += kRecord) {
      const double* d = recv_buf_.data() + r;
      ghosts_.push_back({static_cast<std::int64_t>(std::llround(d[0])),
                         {d[1], d[2], d[3]},
                         {d[4], d[5], d[6]},
                         d[7]});
    }
  }
  ++profile_.exchanges;
  profile_.seconds_waiting += waiting;
  profile_.seconds_packing += MPI_Wtime() - start - waiting;
  return ghosts_;
}

void PointGhostsAcrossPrograms::return_forces(const std::vector<Vec3>& force) {
  const double start = MPI_Wtime();
  requests_.assign(peers_.size(), MPI_REQUEST_NULL);
  std::size_t first = 0;
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    auto& buf = send_buf_[p];
    buf.clear();
    for (std::size_t k = first; k < first + received_[p]; ++k) {
      buf.insert(buf.end(), force[k].begin(), force[k].end());
    }
    first += received_[p];
    mpi::check(MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, peers_[p], kForceTag,
                         inter_, &requests_[p]),
               "MPI_Isend (ghost forces across programs)");
    profile_.bytes_sent += static_cast<std::int64_t>(buf.size() * sizeof(double));
  }
  profile_.messages_sent += static_cast<std::int64_t>(peers_.size());
  const double posted = MPI_Wtime();
  mpi::check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
             "MPI_Waitall (ghost forces across programs)");
  profile_.seconds_packing += posted - start;
  profile_.seconds_waiting += MPI_Wtime() - posted;
}

void PointGhostsAcrossPrograms::collect_forces(std::vector<Vec3>& force) {
  const double start = MPI_Wtime();
  double waiting = 0.0;
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    const auto& from = sent_from_[p];
    recv_buf_.resize(3 * from.size());
    const double before = MPI_Wtime();
    mpi::check(MPI_Recv(recv_buf_.data(), static_cast<int>(recv_buf_.size()), MPI_DOUBLE, peers_[p],
                        kForceTag, inter_, MPI_STATUS_IGNORE),
               "MPI_Recv (ghost forces across programs)");
    waiting += MPI_Wtime() - before;
    profile_.bytes_received += static_cast<std::int64_t>(recv_buf_.size() * sizeof(double));
    for (std::size_t k = 0; k < from.size(); ++k) {
      for (std::size_t a = 0; a < 3; ++a) force[from[k]][a] += recv_buf_[3 * k + a];
    }
  }
  profile_.seconds_waiting += waiting;
  profile_.seconds_packing += MPI_Wtime() - start - waiting;
}

}  // namespace pbms::coupling
