// The ghost exchange across programs (METHOD.md §3, step 1): the ranks of
// one program (the MPM side) send the ranks of another (the DPD side)
// their points within `reach` (cutoff + skin) of the receiver's sub-box,
// so that pair forces can take them as partners. Rank to rank between the
// pairs whose boxes come within reach (found once, from the boxes both
// sides exchange at set-up); periodic images arrive already shifted next
// to the receiver. Never through a root, and the coupler is not involved.
//
// The receiver says along which axes it wants images: none where its own
// neighbour list already wraps around the box (a DPD rank that spans a
// periodic axis), the box length where it does not. Under the
// momentum-conserving interface the receiver sends each ghost's pair
// force back to the rank that owns the point (return_forces /
// collect_forces).
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

#include "pbms/coupling/nodal_sum_across_programs.hpp"

namespace pbms::coupling {

using Vec3 = std::array<double, 3>;

// [lo, hi) per axis; ±infinity where a rank owns everything beyond the box.
struct SpaceBox {
  Vec3 lo{};
  Vec3 hi{};
};

// The periodic lengths of the body's box (0 on axes that are not periodic).
struct PeriodicLengths {
  Vec3 length{0.0, 0.0, 0.0};
};

// One ghost: a point of the sending program, at the image next to the
// receiver's box.
struct GhostPoint {
  std::int64_t id = 0;
  Vec3 x{};
  Vec3 v{};
  double mass = 0.0;
};

class PointGhostsAcrossPrograms {
 public:
  enum class Side { kSender, kReceiver };

  // Collective over both programs' ranks (one exchange of boxes over the
  // intercommunicator `inter`, which must outlive this). A sender passes
  // the box its points lie in; a receiver the box it needs ghosts around
  // and the periodic lengths along which it needs images (a sender's
  // `periodic` is not used).
  PointGhostsAcrossPrograms(MPI_Comm inter, Side side, const SpaceBox& box, double reach,
                            const PeriodicLengths& periodic);

  // New boxes (and a receiver's images), for particles that moved: the
  // same collective exchange as at construction, both programs together.
  void update_boxes(const SpaceBox& box, const PeriodicLengths& periodic);

  // Sender: every point within reach of each receiver that needs it.
  void send(const std::vector<std::int64_t>& id, const std::vector<Vec3>& x,
            const std::vector<Vec3>& v, const std::vector<double>& mass);
  // Sender: the same points as the last send(), to the same receivers at
  // the same images, at their new positions and velocities (indexed like
  // that send's points; no point may have been added, removed or
  // reordered since). Lets a receiver keep its neighbour list.
  void resend(const std::vector<Vec3>& x, const std::vector<Vec3>& v);
  // Receiver: the ghosts of this step, by sender rank then sender order.
  const std::vector<GhostPoint>& receive();

  // Receiver: a force on each ghost of the last receive(), in its order,
  // sent back to the ghost's sender.
  void return_forces(const std::vector<Vec3>& force);
  // Sender: adds the forces the receivers returned for the points of the
  // last send() to `force`, indexed like those points (images of one
  // point all add to it).
  void collect_forces(std::vector<Vec3>& force);

  // Ranks of the other program this one exchanges with (each step).
  [[nodiscard]] const std::vector<int>& peers() const { return peers_; }
  [[nodiscard]] const ExchangeProfile& profile() const { return profile_; }

 private:
  // The shifts (in periodic lengths) under which `from` comes within reach
  // of `to`.
  [[nodiscard]] std::vector<std::array<int, 3>> images(const SpaceBox& from, const SpaceBox& to,
                                                       const PeriodicLengths& periodic) const;
  // Appends each image of one point within reach of peer p; returns how many.
  int append_images(std::int64_t id, const Vec3& x, const Vec3& v, double mass, std::size_t p,
                    std::vector<double>& buf, std::vector<Vec3>& shifts) const;
  void post_sends();

  MPI_Comm inter_;
  Side side_;
  double reach_;
  PeriodicLengths periodic_;
  SpaceBox box_;
  std::vector<SpaceBox> remote_boxes_;
  std::vector<PeriodicLengths> remote_images_;  // what each receiver asked for
  std::vector<int> peers_;
  std::vector<std::vector<std::size_t>> sent_from_;  // sender: the point of each record, per peer
  std::vector<std::vector<Vec3>> sent_shift_;        // and the image shift it was sent at
  std::vector<std::size_t> received_;                // receiver: ghosts from each peer
  std::vector<std::vector<double>> send_buf_;
  std::vector<MPI_Request> requests_;
  std::vector<double> recv_buf_;
  std::vector<GhostPoint> ghosts_;
  ExchangeProfile profile_;
};

}  // namespace pbms::coupling
