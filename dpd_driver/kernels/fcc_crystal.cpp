#include "kernels/fcc_crystal.hpp"

#include "pbms/error.hpp"

namespace pbms::dpd {

FccCrystal fcc_crystal(int cells_x, int cells_y, int cells_z, double lattice_constant,
                       double mass) {
  if (cells_x <= 0 || cells_y <= 0 || cells_z <= 0) {
    throw Error("fcc crystal: cell counts must be positive");
  }
  if (!(lattice_constant > 0.0)) throw Error("fcc crystal: lattice constant must be > 0 Å");
  FccCrystal crystal;
  crystal.box.hi = {cells_x * lattice_constant, cells_y * lattice_constant,
                    cells_z * lattice_constant};
  crystal.particles.mass_per_type = {mass};
  std::int64_t id = 1;
  for (int k = 0; k < cells_z; ++k) {
    for (int j = 0; j < cells_y; ++j) {
      for (int i = 0; i < cells_x; ++i) {
        for (const Vec3& b : kFccBasis) {
          crystal.particles.add(id++, 0,
                                {(i + b[0]) * lattice_constant, (j + b[1]) * lattice_constant,
                                 (k + b[2]) * lattice_constant});
        }
      }
    }
  }
  return crystal;
}

}  // namespace pbms::dpd
