#include "stage/dpd_gauge.hpp"

#include <mpi.h>

#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

DpdGauge::DpdGauge(const analysis::GaugeSection& gauge, const DpdParticles& all,
                   std::uint32_t specimen, int axis, double plane)
    : gauge_(gauge), specimen_(specimen), axis_(axis), plane_(plane) {
  for (std::size_t i = 0; i < all.size(); ++i) {
    if ((all.group_mask[i] & specimen) != 0) start_.emplace(all.id[i], all.x[i][axis]);
  }
}

void DpdGauge::sample(const DpdEngine& engine) {
  const DpdParticles& p = engine.particles();
  const OrthogonalBox& box = engine.domain().box();
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  auto unwrapped = [&](std::size_t i, int a) { return p.x[i][a] + p.image[i][a] * box.length(a); };
  analysis::GaugeSums g;
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    if ((p.group_mask[i] & specimen_) == 0) continue;
    const double x0 = start_.at(p.id[i]);
    g.add_force(gauge_.weight(x0), p.f[i][axis_]);
    const int h = gauge_.half(x0);
    if (h >= 0) g.add_member(h, unwrapped(i, axis_), {unwrapped(i, a1), unwrapped(i, a2)});
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, g.sums.data(), static_cast<int>(g.sums.size()), MPI_DOUBLE,
                           MPI_SUM, engine.comm()),
             "MPI_Allreduce");
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, g.minima.data(), static_cast<int>(g.minima.size()),
                           MPI_DOUBLE, MPI_MIN, engine.comm()),
             "MPI_Allreduce");
  const double distance = g.centroid_distance();
  const double extents = g.cross_section(plane_);
  if (strain_.empty()) {
    distance0_ = distance;
    extents0_ = extents;
    if (area0_ <= 0.0) area0_ = extents;
  }
  strain_.push_back(distance / distance0_ - 1.0);
  // The mean force across the gauge's planes over its section; eV/Å^3 to GPa.
  const double area = area0_ * extents / extents0_;
  stress_.push_back(g.sums[0] / area * units::kBarPerEvPerA3 / units::kBarPerGPa);
}

void DpdGauge::report(const analysis::TensionTest& test, StageResults& r,
                      const std::string& stage) const {
  test.report_gauge(r, strain_, stress_, stage);
}

void DpdGauge::save(CheckpointArchive& a) const {
  a.put("gauge/measures", std::vector<double>{distance0_, area0_, extents0_});
  a.put("gauge/strain", strain_);
  a.put("gauge/stress", stress_);
}

void DpdGauge::load(const CheckpointArchive& a) {
  const auto& m = a.get("gauge/measures");
  distance0_ = m.at(0);
  area0_ = m.at(1);
  extents0_ = m.at(2);
  strain_ = a.get("gauge/strain");
  stress_ = a.get("gauge/stress");
}

}  // namespace pbms::dpd
