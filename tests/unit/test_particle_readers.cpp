#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/io/h5md_reader.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/io/hdf5.hpp"
#include "pbms/io/lammps_data_reader.hpp"

namespace fs = std::filesystem;
using pbms::h5::Handle;

namespace {

class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("pbms_readers_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The message of the pbms::Error that `f` throws, or "" if none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const pbms::Error& e) {
    return e.what();
  }
  return "";
}

// --- raw HDF5, to build files the way other writers lay them out ----------

Handle make_dataset(hid_t parent, const char* name, hid_t type, std::vector<hsize_t> dims,
                    const void* data) {
  Handle space(dims.empty() ? H5Screate(H5S_SCALAR)
                            : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
               H5Sclose);
  Handle ds(H5Dcreate2(parent, name, type, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            H5Dclose);
  H5Dwrite(ds.id(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  return ds;
}

// pbms::h5::require_group one component at a time: given a path whose
// parent is missing, it lets HDF5 print an error stack before creating it.
Handle group_path(hid_t parent, const std::string& path) {
  Handle g = pbms::h5::require_group(parent, path.substr(0, path.find('/')));
  if (path.find('/') == std::string::npos) return g;
  return group_path(g.id(), path.substr(path.find('/') + 1));
}

// ch5md (LAMMPS `dump h5md`) sizes strings to their length, leaving no
// room for a terminator; the reader must cope.
void unterminated_string_attribute(hid_t obj, const char* name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H5Awrite(attr.id(), type.id(), value.data());
}

void boundary_attribute(hid_t box, const std::array<const char*, 3>& b) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), 9);
  char buf[27] = {};
  for (int a = 0; a < 3; ++a) std::snprintf(buf + 9 * a, 9, "%s", b[a]);
  const hsize_t three = 3;
  Handle space(H5Screate_simple(1, &three, nullptr), H5Sclose);
  Handle attr(H5Acreate2(box, "boundary", type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  H5Awrite(attr.id(), type.id(), buf);
}

// --- H5MD -----------------------------------------------------------------

TEST(H5mdReader, RoundTripThroughWriter) {
  ScratchDir dir;
  const auto path = dir.file("traj.h5md");
  // Ids out of order, so that a reader inventing 0..N-1 shows. The file
  // holds them in ascending id: given particles 1, 2, 0.
  const std::vector<int64_t> ids = {7, 3, 5};
  const std::vector<size_t> given = {1, 2, 0};
  const std::vector<int> species = {0, 1, 0};
  const std::vector<double> x0 = {0.1, 0.2, 0.3, 1.1, 1.2, 1.3, 2.1, 2.2, 2.3};
  const std::vector<double> x1 = {0.4, 0.5, 0.6, 1.4, 1.5, 1.6, 2.4, 2.5, 2.6};
  const std::vector<double> v0(9, 0.0), v1 = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<double> f0(9, -1.0), f1 = {-1, -2, -3, -4, -5, -6, -7, -8, -9};
  const std::vector<double> e0 = {0.5, 0.6, 0.7}, e1 = {1.5, 1.6, 1.7};
  {
    pbms::H5mdWriter::Options opt;
    opt.path = path;
    opt.periodic = {true, false, true};
    opt.velocities = true;
    opt.forces = true;
    opt.internal_energy = true;
    pbms::H5mdWriter w(MPI_COMM_SELF, opt, ids, species);
    w.write_frame(0, 0.0, {10, 11, 12}, ids, x0, v0, f0, e0);
    w.write_frame(20, 0.04, {10, 11, 12.5}, ids, x1, v1, f1, e1);
    // A refused frame leaves every series as it was.
    EXPECT_THROW(w.write_frame(30, 0.06, {10, 11, 12.5}, ids, x1, v1, {1.0}, e1), pbms::Error);
    EXPECT_THROW(w.write_frame(30, 0.06, {10, 11, 12.5}, ids, x1, v1, f1, {1.0}), pbms::Error);
    EXPECT_THROW(w.write_frame(30, 0.06, {10, 11, 12.5}, {7, 3, 4}, x1, v1, f1, e1), pbms::Error);
    EXPECT_EQ(w.frames(), 2);
  }

  const auto last = pbms::read_h5md_particles(path);
  EXPECT_EQ(last.step, 20);
  EXPECT_DOUBLE_EQ(last.time, 0.04);
  EXPECT_EQ(last.id, (std::vector<int64_t>{3, 5, 7}));
  EXPECT_EQ(last.species, (std::vector<int>{1, 0, 0}));
  ASSERT_EQ(last.x.size(), 3u);
  ASSERT_TRUE(last.has_velocities);
  for (size_t i = 0; i < 3; ++i) {
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(last.x[i][c], x1[3 * given[i] + c]);
      EXPECT_DOUBLE_EQ(last.v[i][c], v1[3 * given[i] + c]);
    }
  }
  EXPECT_EQ(last.box_lo, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(last.box_hi, (std::array<double, 3>{10, 11, 12.5}));
  EXPECT_EQ(last.periodic, (std::array<bool, 3>{true, false, true}));
  EXPECT_TRUE(last.image.empty());
  EXPECT_TRUE(last.mass_per_type.empty());

  const auto first = pbms::read_h5md_particles(path, "all", 0);
  EXPECT_EQ(first.step, 0);
  EXPECT_DOUBLE_EQ(first.x[1][1], 2.2);
  EXPECT_EQ(first.box_hi[2], 12.0);
  EXPECT_EQ(pbms::read_h5md_particles(path, "", -2).step, 0);
  const auto range = error_of([&] { pbms::read_h5md_particles(path, "", 2); });
  EXPECT_NE(range.find(path), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;

  // Forces and internal energy are not part of a snapshot; check the file.
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  auto read_all = [&](const char* name, std::vector<hsize_t> want_dims, const char* unit,
                      const char* unit_attribute = "unit") {
    Handle ds(H5Dopen2(f.id(), name, H5P_DEFAULT), H5Dclose);
    Handle space(H5Dget_space(ds.id()), H5Sclose);
    std::vector<hsize_t> dims(static_cast<size_t>(H5Sget_simple_extent_ndims(space.id())));
    H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
    EXPECT_EQ(dims, want_dims) << name;
    // Units are variable-length strings (h5py, and so MDAnalysis, reads
    // them as str).
    Handle attr(H5Aopen(ds.id(), unit_attribute, H5P_DEFAULT), H5Aclose);
    Handle type(H5Aget_type(attr.id()), H5Tclose);
    EXPECT_GT(H5Tis_variable_str(type.id()), 0) << name;
    char* text = nullptr;
    H5Aread(attr.id(), type.id(), &text);
    EXPECT_STREQ(text, unit) << name;
    H5free_memory(text);
    std::vector<double> v(static_cast<size_t>(H5Sget_simple_extent_npoints(space.id())));
    H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    return v;
  };
  // Forces stay in eV/angstrom; their unit is under `pbms_unit`, which
  // MDAnalysis does not read (it refuses force units it does not know).
  const auto force = read_all("particles/all/force/value", {2, 3, 3}, "eV Angstrom-1", "pbms_unit");
  EXPECT_EQ(H5Aexists_by_name(f.id(), "particles/all/force/value", "unit", H5P_DEFAULT), 0);
  for (size_t i = 0; i < 9; ++i) {
    EXPECT_EQ(force[i], f0[3 * given[i / 3] + i % 3]);
    EXPECT_EQ(force[9 + i], f1[3 * given[i / 3] + i % 3]);
  }
  read_all("particles/all/position/value", {2, 3, 3}, "Angstrom");
  read_all("particles/all/velocity/value", {2, 3, 3}, "Angstrom ps-1");
  read_all("particles/all/position/time", {2}, "ps");
  // The box as a diagonal matrix per frame: MDAnalysis reads the vector
  // form of H5MD as an empty box.
  const auto edges = read_all("particles/all/box/edges/value", {2, 3, 3}, "Angstrom");
  EXPECT_EQ(edges, (std::vector<double>{10, 0, 0, 0, 11, 0, 0, 0, 12,  //
                                        10, 0, 0, 0, 11, 0, 0, 0, 12.5}));
  const auto energy = read_all("particles/all/internal_energy/value", {2, 3}, "eV");
  EXPECT_EQ(energy, (std::vector<double>{0.6, 0.7, 0.5, 1.6, 1.7, 1.5}));
  EXPECT_GT(H5Lexists(f.id(), "particles/all/internal_energy/step", H5P_DEFAULT), 0);
}

// An MPM run in consistent units: no unit is claimed, nothing is converted.
TEST(H5mdWriter, ConsistentUnitsCarryNoUnitAttributes) {
  ScratchDir dir;
  const auto path = dir.file("unitless.h5md");
  const std::vector<double> x = {0.1, 0.2, 0.3}, v = {1, 2, 3}, f = {-1, -2, -3};
  {
    pbms::H5mdWriter::Options opt;
    opt.path = path;
    opt.metal_units = false;
    opt.velocities = true;
    opt.forces = true;
    pbms::H5mdWriter w(MPI_COMM_SELF, opt, {0}, {0});
    w.write_frame(0, 0.5, {1, 1, 1}, {0}, x, v, f);
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  for (const char* name : {"particles/all/position/value", "particles/all/position/time",
                           "particles/all/velocity/value", "particles/all/force/value",
                           "particles/all/box/edges/value"}) {
    Handle ds(H5Dopen2(file.id(), name, H5P_DEFAULT), H5Dclose);
    EXPECT_EQ(H5Aexists(ds.id(), "unit"), 0) << name;
  }
  Handle ds(H5Dopen2(file.id(), "particles/all/force/value", H5P_DEFAULT), H5Dclose);
  std::vector<double> stored(3);
  H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, stored.data());
  EXPECT_EQ(stored, f);
  EXPECT_EQ(pbms::read_h5md_particles(path).x[0], (std::array<double, 3>{0.1, 0.2, 0.3}));
}

// --- updates by copy and rename (results.h5) --------------------------------

namespace {
double read_scalar(const std::string& path, const char* name) {
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  Handle ds(H5Dopen2(f.id(), name, H5P_DEFAULT), H5Dclose);
  double v = 0;
  H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
  return v;
}
}  // namespace

TEST(H5Update, PublishedWhenClosedWhileAReaderHoldsTheOldFile) {
  ScratchDir dir;
  const auto path = dir.file("results.h5");
  {
    Handle f = pbms::h5::open_or_create(path);
    pbms::h5::write_scalar(f.id(), "a", 1.0, "1");
    EXPECT_FALSE(fs::exists(path)) << "published before the handle closed";
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(read_scalar(path, "a"), 1.0);

  // A reader keeps the file open (and, with HDF5 1.10, locked) throughout.
  Handle reader(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  {
    Handle f = pbms::h5::open_or_create(path);
    pbms::h5::write_scalar(f.id(), "b", 2.0, "1");
    EXPECT_EQ(H5Lexists(reader.id(), "b", H5P_DEFAULT), 0) << "the reader saw half an update";
  }
  EXPECT_EQ(H5Lexists(reader.id(), "b", H5P_DEFAULT), 0);
  reader.reset();
  EXPECT_EQ(read_scalar(path, "a"), 1.0);
  EXPECT_EQ(read_scalar(path, "b"), 2.0);
}

TEST(H5Update, DroppedWhenAnExceptionUnwinds) {
  ScratchDir dir;
  const auto path = dir.file("results.h5");
  {
    Handle f = pbms::h5::open_or_create(path);
    pbms::h5::write_scalar(f.id(), "a", 1.0, "1");
  }
  try {
    Handle f = pbms::h5::open_or_create(path);
    pbms::h5::write_scalar(f.id(), "a", 5.0, "1");
    throw pbms::Error("a stage's results could not be stored");
  } catch (const pbms::Error&) {
  }
  EXPECT_EQ(read_scalar(path, "a"), 1.0);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  // A copy left behind by a crash does not stand in for a missing file.
  const auto fresh = dir.file("fresh.h5");
  write_text(fresh + ".tmp", "stale");
  {
    Handle f = pbms::h5::open_or_create(fresh);
    pbms::h5::write_scalar(f.id(), "c", 3.0, "1");
  }
  EXPECT_EQ(read_scalar(fresh, "c"), 3.0);
}

// The layout of LAMMPS `dump h5md ... position image velocity every 2
// species`: step and time of box/edges and image are hard links to those of
// position, velocity has its own (every second frame), species is a time
// series of 1-based LAMMPS types, there are no ids.
TEST(H5mdReader, ReadsLammpsDumpLayout) {
  ScratchDir dir;
  const auto path = dir.file("lammps.h5");
  {
    Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    auto creator = group_path(f.id(), "h5md/creator");
    unterminated_string_attribute(creator.id(), "name", "lammps");
    auto all = group_path(f.id(), "particles/all");
    const int steps[2] = {0, 10}, vsteps[1] = {0};
    const double times[2] = {0.0, 0.01}, vtimes[1] = {0.0};
    auto position = pbms::h5::require_group(all.id(), "position");
    make_dataset(position.id(), "step", H5T_NATIVE_INT, {2}, steps);
    make_dataset(position.id(), "time", H5T_NATIVE_DOUBLE, {2}, times);
    const double x[2][2][3] = {{{1, 2, 3}, {4, 5, 6}}, {{1.5, 2, 3}, {4.5, 5, 6}}};
    make_dataset(position.id(), "value", H5T_NATIVE_DOUBLE, {2, 2, 3}, x);
    auto link_clock = [&](hid_t group) {
      H5Lcreate_hard(position.id(), "step", group, "step", H5P_DEFAULT, H5P_DEFAULT);
      H5Lcreate_hard(position.id(), "time", group, "time", H5P_DEFAULT, H5P_DEFAULT);
    };
    auto image = pbms::h5::require_group(all.id(), "image");
    link_clock(image.id());
    const int img[2][2][3] = {{{0, 0, 0}, {0, 0, 0}}, {{1, 0, -1}, {0, 2, 0}}};
    make_dataset(image.id(), "value", H5T_NATIVE_INT, {2, 2, 3}, img);
    auto box = pbms::h5::require_group(all.id(), "box");
    {
      const int three = 3;
      Handle space(H5Screate(H5S_SCALAR), H5Sclose);
      Handle attr(
          H5Acreate2(box.id(), "dimension", H5T_NATIVE_INT, space.id(), H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose);
      H5Awrite(attr.id(), H5T_NATIVE_INT, &three);
    }
    boundary_attribute(box.id(), {"periodic", "periodic", "none"});
    auto edges = pbms::h5::require_group(box.id(), "edges");
    link_clock(edges.id());
    const double e[2][3] = {{8, 9, 10}, {8, 9, 11}};
    make_dataset(edges.id(), "value", H5T_NATIVE_DOUBLE, {2, 3}, e);
    auto velocity = pbms::h5::require_group(all.id(), "velocity");
    make_dataset(velocity.id(), "step", H5T_NATIVE_INT, {1}, vsteps);
    make_dataset(velocity.id(), "time", H5T_NATIVE_DOUBLE, {1}, vtimes);
    const double v[1][2][3] = {{{0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}}};
    make_dataset(velocity.id(), "value", H5T_NATIVE_DOUBLE, {1, 2, 3}, v);
    auto species = pbms::h5::require_group(all.id(), "species");
    make_dataset(species.id(), "step", H5T_NATIVE_INT, {2}, steps);
    make_dataset(species.id(), "time", H5T_NATIVE_DOUBLE, {2}, times);
    const int types[2][2] = {{1, 2}, {1, 2}};
    make_dataset(species.id(), "value", H5T_NATIVE_INT, {2, 2}, types);
  }
  const auto last = pbms::read_h5md_particles(path);
  EXPECT_EQ(last.step, 10);
  EXPECT_DOUBLE_EQ(last.time, 0.01);
  EXPECT_EQ(last.id, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(last.species, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(last.x[1][0], 4.5);
  EXPECT_FALSE(last.has_velocities);  // none stored at step 10
  ASSERT_EQ(last.v.size(), 2u);
  EXPECT_EQ(last.v[1], (std::array<double, 3>{0, 0, 0}));
  ASSERT_EQ(last.image.size(), 2u);
  EXPECT_EQ(last.image[0], (std::array<int, 3>{1, 0, -1}));
  EXPECT_EQ(last.box_hi, (std::array<double, 3>{8, 9, 11}));
  EXPECT_EQ(last.periodic, (std::array<bool, 3>{true, true, false}));

  const auto first = pbms::read_h5md_particles(path, "all", 0);
  EXPECT_TRUE(first.has_velocities);
  EXPECT_DOUBLE_EQ(first.v[1][2], 0.6);
  EXPECT_EQ(first.box_hi[2], 10.0);
}

// LAMMPS `dump h5md 0 ...` writes fixed datasets (no step, no time), and
// other writers may give a full edge matrix and fixed ids.
TEST(H5mdReader, ReadsFixedDatasetsAndEdgeMatrix) {
  ScratchDir dir;
  const auto path = dir.file("fixed.h5");
  {
    Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    auto all = group_path(f.id(), "particles/crystal");
    const double x[3][3] = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    make_dataset(all.id(), "position", H5T_NATIVE_DOUBLE, {3, 3}, x);
    const long long id[3] = {10, 20, 30};
    make_dataset(all.id(), "id", H5T_NATIVE_LLONG, {3}, id);
    const int species[3] = {2, 0, 1};
    make_dataset(all.id(), "species", H5T_NATIVE_INT, {3}, species);
    auto box = pbms::h5::require_group(all.id(), "box");
    boundary_attribute(box.id(), {"none", "none", "none"});
    const double m[3][3] = {{5, 0, 0}, {0, 6, 0}, {0, 0, 7}};
    make_dataset(box.id(), "edges", H5T_NATIVE_DOUBLE, {3, 3}, m);
  }
  const auto s = pbms::read_h5md_particles(path);
  EXPECT_EQ(s.step, 0);
  EXPECT_EQ(s.id, (std::vector<int64_t>{10, 20, 30}));
  EXPECT_EQ(s.species, (std::vector<int>{2, 0, 1}));
  EXPECT_FALSE(s.has_velocities);
  EXPECT_EQ(s.box_hi, (std::array<double, 3>{5, 6, 7}));
  EXPECT_EQ(s.periodic, (std::array<bool, 3>{false, false, false}));
  const auto frame = error_of([&] { pbms::read_h5md_particles(path, "", 1); });
  EXPECT_NE(frame.find("out of range"), std::string::npos) << frame;
}

TEST(H5mdReader, ErrorsNameTheFileAndWhatIsMissing) {
  ScratchDir dir;
  const auto missing = dir.file("absent.h5md");
  auto msg = error_of([&] { pbms::read_h5md_particles(missing); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;

  const auto text = dir.file("text.h5md");
  write_text(text, "not HDF5\n");
  msg = error_of([&] { pbms::read_h5md_particles(text); });
  EXPECT_NE(msg.find(text), std::string::npos) << msg;

  const auto path = dir.file("nopos.h5md");
  {
    Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    group_path(f.id(), "particles/all/box");
  }
  msg = error_of([&] { pbms::read_h5md_particles(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("particles/all/position"), std::string::npos) << msg;
  msg = error_of([&] { pbms::read_h5md_particles(path, "fluid"); });
  EXPECT_NE(msg.find("particles/fluid"), std::string::npos) << msg;
  EXPECT_NE(msg.find("all"), std::string::npos) << msg;

  // A position series whose box has no edges.
  const auto noedges = dir.file("noedges.h5md");
  {
    Handle f(H5Fcreate(noedges.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    auto all = group_path(f.id(), "particles/all");
    const double x[3] = {0, 0, 0};
    make_dataset(all.id(), "position", H5T_NATIVE_DOUBLE, {1, 3}, x);
    auto box = pbms::h5::require_group(all.id(), "box");
    boundary_attribute(box.id(), {"periodic", "periodic", "periodic"});
  }
  msg = error_of([&] { pbms::read_h5md_particles(noedges); });
  EXPECT_NE(msg.find("particles/all/box/edges"), std::string::npos) << msg;
}

// --- LAMMPS data files ----------------------------------------------------

const char* const kSmallData = R"(Small test file, its title line is never parsed: 1 atoms

3 atoms   # three of them
2 atom types
0 bonds

-1.0 9.0 xlo xhi
0.0 10.0 ylo yhi
2.0 4.5 zlo zhi

Masses

2 4.0026  # He
1 63.546

Pair Coeffs # lj/cut

1 0.0103 3.4
2 0.0009 2.6

Atoms # atomic

3 2 3.0 3.1 3.2 0 0 1
1 1 1.0 1.1 1.2 -1 0 0

2 1 2.0 2.1 2.2 0 1 0

Velocities

2 0.2 0.21 0.22
1 0.1 0.11 0.12
3 0.3 0.31 0.32
)";

TEST(LammpsDataReader, ParsesAtomicDataWithImagesAndVelocities) {
  ScratchDir dir;
  const auto path = dir.file("data.lmp");
  write_text(path, kSmallData);
  const auto s = pbms::read_lammps_data(path);
  EXPECT_EQ(s.id, (std::vector<int64_t>{1, 2, 3}));
  EXPECT_EQ(s.species, (std::vector<int>{0, 0, 1}));
  ASSERT_EQ(s.x.size(), 3u);
  EXPECT_EQ(s.x[0], (std::array<double, 3>{1.0, 1.1, 1.2}));
  EXPECT_EQ(s.x[2], (std::array<double, 3>{3.0, 3.1, 3.2}));
  ASSERT_EQ(s.image.size(), 3u);
  EXPECT_EQ(s.image[0], (std::array<int, 3>{-1, 0, 0}));
  EXPECT_EQ(s.image[2], (std::array<int, 3>{0, 0, 1}));
  ASSERT_TRUE(s.has_velocities);
  EXPECT_EQ(s.v[1], (std::array<double, 3>{0.2, 0.21, 0.22}));
  EXPECT_EQ(s.v[2], (std::array<double, 3>{0.3, 0.31, 0.32}));
  EXPECT_EQ(s.mass_per_type, (std::vector<double>{63.546, 4.0026}));
  EXPECT_EQ(s.box_lo, (std::array<double, 3>{-1.0, 0.0, 2.0}));
  EXPECT_EQ(s.box_hi, (std::array<double, 3>{9.0, 10.0, 4.5}));
  EXPECT_EQ(s.periodic, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(s.step, 0);
}

TEST(LammpsDataReader, WithoutVelocitiesImagesOrMasses) {
  ScratchDir dir;
  const auto path = dir.file("data.lmp");
  write_text(path,
             "title\n2 atoms\n1 atom types\n0 5 xlo xhi\n0 5 ylo yhi\n0 5 zlo zhi\n"
             "Atoms\n2 1 1 1 1\n1 1 0 0 0\n");
  const auto s = pbms::read_lammps_data(path);
  EXPECT_EQ(s.id, (std::vector<int64_t>{1, 2}));
  EXPECT_FALSE(s.has_velocities);
  EXPECT_EQ(s.v.size(), 2u);
  EXPECT_TRUE(s.image.empty());
  EXPECT_TRUE(s.mass_per_type.empty());
}

struct Refusal {
  const char* name;
  std::string text;
  int line;
  const char* says;
};

TEST(LammpsDataReader, RefusalsNameFileAndLine) {
  const std::string head =
      "title\n\n2 atoms\n2 atom types\n0 5 xlo xhi\n0 5 ylo yhi\n0 5 zlo zhi\n";
  // head is lines 1-7; "\nAtoms\n\n" puts Atoms on line 9 and rows from 11.
  const std::vector<Refusal> cases = {
      {"short Atoms line", head + "\nAtoms\n\n1 1 0 0 0\n2 1 0 0\n", 12,
       "Atoms line needs 5 or 8 columns, got 4"},
      {"tilt factors",
       "title\n2 atoms\n2 atom types\n0 5 xlo xhi\n0 5 ylo yhi\n0 5 zlo zhi\n"
       "0.5 0 0 xy xz yz\n",
       7, "triclinic"},
      {"duplicate id", head + "\nAtoms\n\n1 1 0 0 0\n1 2 1 1 1\n", 12, "atom id 1 appears twice"},
      {"count mismatch", head + "\nAtoms\n\n1 1 0 0 0\n2 1 1 1 1\n3 1 2 2 2\n", 9,
       "Atoms section has 3 lines"},
      {"unknown type", head + "\nAtoms\n\n1 1 0 0 0\n2 3 1 1 1\n", 12, "atom type 3"},
      {"other atom style", head + "\nAtoms # full\n\n1 1 1 0 0 0 0\n", 9, "atom style 'full'"},
      {"bad number", head + "\nAtoms\n\n1 1 0 0 0\n2 1 1 one 1\n", 12, "'one'"},
      {"velocity of unknown id",
       head + "\nAtoms\n\n1 1 0 0 0\n2 1 1 1 1\n\nVelocities\n\n1 0 0 0\n4 0 0 0\n", 17,
       "atom id 4"},
  };
  ScratchDir dir;
  const auto path = dir.file("data.lmp");
  for (const auto& c : cases) {
    write_text(path, c.text);
    const auto msg = error_of([&] { pbms::read_lammps_data(path); });
    const auto where = path + ":" + std::to_string(c.line) + ": ";
    EXPECT_EQ(msg.rfind(where, 0), 0u) << c.name << ": " << msg;
    EXPECT_NE(msg.find(c.says), std::string::npos) << c.name << ": " << msg;
  }
}

// Reads what LAMMPS itself writes: a 2x2x2 fcc copper block, 32 atoms.
TEST(LammpsDataReader, ReadsLammpsWriteData) {
  // lmp is a dependency that ./pbms installs: its absence is a failure, not a skip.
  ASSERT_EQ(std::system("command -v lmp > /dev/null 2>&1"), 0)
      << "no lmp on PATH; ./pbms installs it (Debian package lammps)";
  ScratchDir dir;
  write_text(dir.file("in.lmp"),
             "units metal\n"
             "atom_style atomic\n"
             "boundary p p p\n"
             "lattice fcc 3.615\n"
             "region box block 0 2 0 2 0 2\n"
             "create_box 1 box\n"
             "create_atoms 1 box\n"
             "mass 1 63.546\n"
             "velocity all create 300.0 4928459 loop geom\n"
             "write_data data.lmp\n");
  const std::string cmd =
      "cd '" + dir.path().string() + "' && lmp -in in.lmp -log none -screen none > lmp.out 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "lmp failed; see " << dir.file("lmp.out");
  const auto s = pbms::read_lammps_data(dir.file("data.lmp"));
  ASSERT_EQ(s.id.size(), 32u);
  EXPECT_EQ(s.id.front(), 1);
  EXPECT_EQ(s.id.back(), 32);
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(s.box_lo[a], 0.0);
    EXPECT_NEAR(s.box_hi[a], 2 * 3.615, 1e-9);
  }
  EXPECT_EQ(s.mass_per_type, (std::vector<double>{63.546}));
  EXPECT_EQ(s.species, std::vector<int>(32, 0));
  ASSERT_TRUE(s.has_velocities);
  double v2 = 0;
  for (const auto& v : s.v) v2 += v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  EXPECT_GT(v2, 0.0);
  EXPECT_EQ(s.image.size(), 32u);
}

}  // namespace
