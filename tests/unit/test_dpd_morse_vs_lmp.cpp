// The morse pair style against LAMMPS itself (Debian's lmp, pair_style
// morse), not against a formula of ours: energy, forces and virial of a
// random 500-particle configuration with the copper mesoparticle parameters
// (docs/dpd-morse-fit.md, configs/potentials/cu_cg_morse.yaml) must agree
// to 1e-10 relative, unshifted and with pair_modify shift yes, for a
// periodic box, a free cluster and a slab (periodic in x and y only). 1e-10
// leaves room for summation order and branch_free_exp (2 ulp), and none for
// a wrong term or a missed image.
//
// Fails when lmp is not on PATH: lmp is one of the Debian packages that
// ./pbms installs, and ctest would count a skipped test as passed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cu_cg_morse.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "stage/dpd_model.hpp"

using namespace pbms::dpd;
namespace fs = std::filesystem;

namespace {

constexpr double kMass = 508.37;  // g/mol
constexpr int kCount = 500;
// Closer pairs than this would dominate the force scale and hide the error
// of the ordinary pairs in max |f|; 4 Å is 0.7 r0.
constexpr double kMinDistance = 4.0;  // Å
// LAMMPS metal nktv2p (update.cpp): pressure = virial / V · nktv2p.
constexpr double kNktv2p = 1.6021765e6;
constexpr double kTolerance = 1e-10;

struct Geometry {
  const char* name;
  std::array<bool, 3> periodic;
};

// Names the parameter in test listings (ctest shows a byte dump otherwise).
void PrintTo(const Geometry& geometry, std::ostream* out) {
  *out << geometry.name;
}

// 500 particles in a 36 × 40 × 44 Å box (every periodic length ≥ 2 r_c, so
// the minimum image is the only image in reach), no two closer than
// kMinDistance under the periodic minimum image, which is the strictest
// distance of the three geometries. About 40 neighbours inside r_c each.
DpdParticles random_configuration(const OrthogonalBox& box) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  OrthogonalBox all_periodic = box;
  all_periodic.periodic = {true, true, true};
  DpdParticles p;
  p.mass_per_type = {kMass};
  while (static_cast<int>(p.size()) < kCount) {
    Vec3 x{};
    for (int a = 0; a < 3; ++a) x[a] = box.lo[a] + u(rng) * box.length(a);
    bool clear = true;
    for (const auto& y : p.x) {
      const Vec3 d = all_periodic.minimum_image({x[0] - y[0], x[1] - y[1], x[2] - y[2]});
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < kMinDistance * kMinDistance) {
        clear = false;
        break;
      }
    }
    if (clear) p.add(static_cast<std::int64_t>(p.size()) + 1, 0, x);
  }
  return p;
}

struct Reference {
  double energy = 0.0;             // eV
  std::array<double, 6> virial{};  // eV, LAMMPS order
  std::vector<Vec3> f;             // eV/Å, by id − 1
};

// LAMMPS' results for one shift setting, from the files the input writes.
Reference read_reference(const fs::path& dir, const std::string& tag) {
  Reference ref;
  std::ifstream results(dir / ("thermo_" + tag + ".txt"));
  std::string key;
  double volume = 0.0;
  std::array<double, 6> pressure{};
  while (results >> key) {
    if (key == "energy") {
      results >> ref.energy;
    } else if (key == "volume") {
      results >> volume;
    } else if (key == "pressure") {
      for (double& p : pressure) results >> p;
    }
  }
  EXPECT_GT(volume, 0.0) << "no thermo output from lmp for " << tag;
  for (int c = 0; c < 6; ++c) ref.virial[c] = pressure[c] * volume / kNktv2p;

  // A custom dump: 9 header lines, then "id fx fy fz" sorted by id.
  std::ifstream dump(dir / ("forces_" + tag + ".txt"));
  std::string line;
  for (int k = 0; k < 9 && std::getline(dump, line); ++k) {
  }
  ref.f.assign(kCount, {0.0, 0.0, 0.0});
  long id = 0;
  Vec3 f{};
  int read = 0;
  while (dump >> id >> f[0] >> f[1] >> f[2]) {
    if (id >= 1 && id <= kCount) ref.f[id - 1] = f;
    ++read;
  }
  EXPECT_EQ(read, kCount) << "force dump of lmp for " << tag;
  return ref;
}

void write_data_file(const fs::path& path, const DpdParticles& p, const OrthogonalBox& box) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  ASSERT_NE(out, nullptr);
  std::fprintf(out, "PBMS morse vs lmp\n\n%zu atoms\n1 atom types\n\n", p.size());
  const char* axis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    std::fprintf(out, "%.17g %.17g %slo %shi\n", box.lo[a], box.hi[a], axis[a], axis[a]);
  }
  std::fprintf(out, "\nMasses\n\n1 %.17g\n\nAtoms # atomic\n\n", kMass);
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::fprintf(out, "%lld 1 %.17g %.17g %.17g\n", static_cast<long long>(p.id[i]), p.x[i][0],
                 p.x[i][1], p.x[i][2]);
  }
  std::fclose(out);
}

// Two runs of 0 steps, unshifted then shifted; each prints E and the pair
// virial (as pressure, the only way LAMMPS reports it) with 17 digits and
// dumps the forces.
void write_input(const fs::path& path, const Geometry& geometry, const CuCgMorseParameters& morse) {
  std::ofstream in(path);
  in << "units metal\natom_style atomic\n";
  in << "boundary";
  for (bool p : geometry.periodic) in << (p ? " p" : " f");
  in << "\nread_data data.lmp\n";
  char coeff[160];
  std::snprintf(coeff, sizeof coeff, "pair_style morse %.17g\npair_coeff 1 1 %.17g %.17g %.17g\n",
                morse.cutoff, morse.d0, morse.alpha, morse.r0);
  in << coeff;
  in << "neighbor 1.0 bin\n";
  // Listed in thermo so that LAMMPS tallies the virial on step 0.
  in << "compute v all pressure NULL virial\n";
  in << "thermo_style custom step pe c_v[1] c_v[2] c_v[3] c_v[4] c_v[5] c_v[6]\n";
  for (const char* tag : {"noshift", "shift"}) {
    if (std::string(tag) == "shift") in << "pair_modify shift yes\n";
    in << "dump f all custom 1 forces_" << tag << ".txt id fx fy fz\n";
    in << "dump_modify f sort id format float %.17g\n";
    in << "run 0\n";
    in << "undump f\n";
    in << "print \"energy $(pe:%.17g)\" file thermo_" << tag << ".txt\n";
    in << "print \"volume $(vol:%.17g)\" append thermo_" << tag << ".txt\n";
    in << "print \"pressure $(c_v[1]:%.17g) $(c_v[2]:%.17g) $(c_v[3]:%.17g) "
          "$(c_v[4]:%.17g) $(c_v[5]:%.17g) $(c_v[6]:%.17g)\" append thermo_"
       << tag << ".txt\n";
  }
}

bool lmp_on_path() {
  return std::system("command -v lmp >/dev/null 2>&1") == 0;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class MorseVsLmp : public ::testing::TestWithParam<Geometry> {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "pbms-morse-lmp.XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

TEST_P(MorseVsLmp, EnergyForcesAndVirialAgreeTo1e10) {
  ASSERT_TRUE(lmp_on_path()) << "lmp is not on PATH; ./pbms installs it (Debian package lammps)";
  const Geometry& geometry = GetParam();
  OrthogonalBox box;
  box.hi = {36.0, 40.0, 44.0};
  box.periodic = geometry.periodic;
  const DpdParticles initial = random_configuration(box);
  const CuCgMorseParameters parameters = cu_cg_morse_parameters();
  // The minimum image is the only image in reach only while 2 r_c fits the box.
  ASSERT_LE(2.0 * parameters.cutoff, std::min({box.length(0), box.length(1), box.length(2)}))
      << "the cutoff in " << kCuCgMorseFile << " is too long for the test box";

  write_data_file(dir_ / "data.lmp", initial, box);
  write_input(dir_ / "in.lmp", geometry, parameters);
  const std::string command = "cd '" + dir_.string() +
                              "' && lmp -in in.lmp -log none -nocite -screen screen.txt"
                              " >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << "lmp failed:\n" << read_text(dir_ / "screen.txt");

  for (const bool shift : {false, true}) {
    SCOPED_TRACE(shift ? "pair_modify shift yes" : "no shift");
    const Reference ref = read_reference(dir_, shift ? "shift" : "noshift");

    // Both settings, whatever the file's `shift`: each must match LAMMPS.
    YAML::Node potential = cu_cg_morse_yaml();
    potential["shift"] = shift;
    const std::unique_ptr<PairStyle> morse = pair_style_from_yaml(potential);
    DpdParticles p = initial;
    HalfNeighbourList list(morse->cutoff(), 1.0);
    list.build(p, box);
    p.zero_forces();
    const PairResult result = morse->compute(p, list, Tally::kEnergyAndVirial);

    const double energy_error = std::abs(result.energy - ref.energy) / std::abs(ref.energy);
    double force_error = 0.0;
    double force_scale = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3& a = p.f[i];
      const Vec3& b = ref.f[p.id[i] - 1];
      force_error = std::max(force_error, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      force_scale = std::max(force_scale, std::hypot(b[0], b[1], b[2]));
    }
    force_error /= force_scale;
    double virial_scale = 0.0;
    for (const double w : ref.virial) virial_scale = std::max(virial_scale, std::abs(w));
    double virial_error = 0.0;
    for (int c = 0; c < 6; ++c) {
      virial_error = std::max(virial_error, std::abs(result.virial[c] - ref.virial[c]));
    }
    virial_error /= virial_scale;

    std::printf(
        "morse vs lmp, %s, %s: E %.17g eV (lmp %.17g); relative errors E %.2e, "
        "f %.2e (max |f| %.3g eV/Å), virial %.2e\n",
        geometry.name, shift ? "shift" : "no shift", result.energy, ref.energy, energy_error,
        force_error, force_scale, virial_error);
    EXPECT_LT(energy_error, kTolerance);
    EXPECT_LT(force_error, kTolerance);
    EXPECT_LT(virial_error, kTolerance);
    // A vacuous comparison (nothing in range, or lmp output not read) would pass the above.
    EXPECT_GT(force_scale, 0.1);
    EXPECT_GT(std::abs(ref.energy), 100.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Geometries, MorseVsLmp,
                         ::testing::Values(Geometry{"periodic", {true, true, true}},
                                           Geometry{"free", {false, false, false}},
                                           Geometry{"slab", {true, true, false}}),
                         [](const ::testing::TestParamInfo<Geometry>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
