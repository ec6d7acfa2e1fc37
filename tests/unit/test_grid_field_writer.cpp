#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/grid/grid_field_writer.hpp"
#include "pbms/grid/regular_grid.hpp"
#include "pbms/io/hdf5.hpp"

using pbms::GridFieldWriter;
using pbms::grid::NodeBox;
using pbms::grid::RegularGrid;
namespace fs = std::filesystem;

namespace {

// Off-origin, non-unit and different node counts per axis, so that a
// swapped axis or a wrong origin order shows.
RegularGrid test_grid() {
  return RegularGrid({-1.3, 2.1, 0.7}, 0.37, {4, 3, 2});  // 5 x 4 x 3 nodes
}

double mass_at(int i, int j, int k, int frame) {
  return 1000.0 * frame + i + 10.0 * j + 100.0 * k;
}
double velocity_at(int i, int j, int k, int c, int frame) {
  return mass_at(i, j, k, frame) + 0.25 * (c + 1);
}

struct Frame {
  std::vector<double> mass, velocity;
};

Frame make_frame(const NodeBox& box, int frame) {
  Frame f;
  f.mass.resize(box.count());
  f.velocity.resize(3 * box.count());
  for (std::int64_t l = 0; l < box.count(); ++l) {
    const auto [i, j, k] = box.ijk_of_local(l);
    f.mass[l] = mass_at(i, j, k, frame);
    for (int c = 0; c < 3; ++c) f.velocity[3 * l + c] = velocity_at(i, j, k, c, frame);
  }
  return f;
}

std::vector<GridFieldWriter::Field> fields_of(const Frame& f) {
  return {{"mass", "kg", 1, f.mass.data()}, {"velocity", "m s-1", 3, f.velocity.data()}};
}

// Unique per process as well as per test: another build's tests may run at
// the same time. Declared first in a test, so that it is removed last, after
// every file in it is closed.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ =
        fs::temp_directory_path() / ("pbms_gfw_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<double> values;
  std::string unit;
};

Dataset read_dataset(hid_t file, const std::string& path) {
  Dataset d;
  pbms::h5::Handle ds(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  pbms::h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
  d.dims.resize(H5Sget_simple_extent_ndims(space.id()));
  H5Sget_simple_extent_dims(space.id(), d.dims.data(), nullptr);
  d.values.resize(H5Sget_simple_extent_npoints(space.id()));
  H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data());
  pbms::h5::Handle attr(H5Aopen(ds.id(), "unit", H5P_DEFAULT), H5Aclose);
  pbms::h5::Handle type(H5Aget_type(attr.id()), H5Tclose);
  std::string unit(H5Tget_size(type.id()), '\0');
  H5Aread(attr.id(), type.id(), unit.data());
  d.unit = unit.c_str();  // drops the padding of a fixed-length string
  return d;
}

double read_double_attribute(hid_t file, const std::string& obj, const std::string& name) {
  double v = 0;
  pbms::h5::Handle attr(H5Aopen_by_name(file, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                        H5Aclose);
  H5Aread(attr.id(), H5T_NATIVE_DOUBLE, &v);
  return v;
}

// Not a parser, but enough to catch unbalanced or crossed elements and a
// second root: every start tag is closed, in order, under one root.
bool well_nested(const std::string& xml) {
  std::vector<std::string> open;
  int roots = 0;
  size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    const size_t end = xml.find('>', pos);
    if (end == std::string::npos) return false;
    const std::string_view tag(xml.data() + pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.starts_with('?') || tag.starts_with('!')) continue;
    if (tag.starts_with('/')) {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
      continue;
    }
    if (open.empty()) ++roots;
    if (!tag.ends_with('/')) open.emplace_back(tag.substr(0, tag.find_first_of(" \t\n/")));
  }
  return open.empty() && roots == 1;
}

size_t count_of(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(GridFieldWriter, FramesReadBackWithShapesValuesAndUnits) {
  const ScratchDir scratch;
  const auto& dir = scratch.path();
  const auto grid = test_grid();
  {
    GridFieldWriter w(MPI_COMM_SELF, (dir / "grid").string(), grid, grid.node_box());
    const auto f0 = make_frame(grid.node_box(), 0);
    const auto f1 = make_frame(grid.node_box(), 1);
    w.write_frame(0, 0.0, fields_of(f0));
    w.write_frame(10, 0.5, fields_of(f1));
    EXPECT_EQ(w.frames(), 2);
  }
  pbms::h5::Handle file(H5Fopen((dir / "grid.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  for (const auto& [group, frame] : {std::pair{"step_0", 0}, std::pair{"step_10", 1}}) {
    const auto mass = read_dataset(file.id(), std::string(group) + "/mass");
    ASSERT_EQ(mass.dims, (std::vector<hsize_t>{3, 4, 5}));  // z slowest
    EXPECT_EQ(mass.unit, "kg");
    const auto vel = read_dataset(file.id(), std::string(group) + "/velocity");
    ASSERT_EQ(vel.dims, (std::vector<hsize_t>{3, 4, 5, 3}));
    EXPECT_EQ(vel.unit, "m s-1");
    for (const auto [i, j, k] : {std::array{0, 0, 0}, std::array{4, 0, 0}, std::array{1, 3, 0},
                                 std::array{2, 1, 2}, std::array{4, 3, 2}}) {
      const size_t at = (static_cast<size_t>(k) * 4 + j) * 5 + i;
      EXPECT_EQ(mass.values[at], mass_at(i, j, k, frame)) << group << " " << i << j << k;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(vel.values[3 * at + c], velocity_at(i, j, k, c, frame));
      }
    }
  }
  EXPECT_EQ(read_double_attribute(file.id(), "step_10", "time"), 0.5);
  EXPECT_EQ(read_double_attribute(file.id(), ".", "cell_size"), 0.37);
}

TEST(GridFieldWriter, XdmfListsEveryFrameAndPointsAtExistingDatasets) {
  const ScratchDir scratch;
  const auto& dir = scratch.path();
  const auto grid = test_grid();
  const auto xdmf = dir / "grid.xdmf";
  std::ofstream(xdmf) << "stale";
  GridFieldWriter w(MPI_COMM_SELF, (dir / "grid").string(), grid, grid.node_box());
  EXPECT_FALSE(fs::exists(xdmf)) << "a stale description must not outlive the truncated file";

  const auto f0 = make_frame(grid.node_box(), 0);
  w.write_frame(0, 0.0, fields_of(f0));
  EXPECT_EQ(count_of(slurp(xdmf), "<Grid Name=\"step_"), 1u);
  const auto f1 = make_frame(grid.node_box(), 1);
  w.write_frame(10, 0.5, fields_of(f1));
  EXPECT_FALSE(fs::exists(dir / "grid.xdmf.tmp"));

  const std::string x = slurp(xdmf);
  EXPECT_TRUE(x.starts_with("<?xml")) << x;
  EXPECT_TRUE(well_nested(x)) << x;
  EXPECT_EQ(count_of(x, "GridType=\"Collection\" CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count_of(x, "<Grid Name=\"step_"), 2u);
  EXPECT_EQ(count_of(x, "<Time Value=\"0\"/>"), 1u);
  EXPECT_EQ(count_of(x, "<Time Value=\"0.5\"/>"), 1u);
  EXPECT_EQ(count_of(x, "TopologyType=\"3DCoRectMesh\" Dimensions=\"3 4 5\""), 2u);
  EXPECT_EQ(count_of(x, "GeometryType=\"ORIGIN_DXDYDZ\""), 2u);
  EXPECT_EQ(count_of(x, ">0.7 2.1 -1.3</DataItem>"), 2u) << "origin must be in z, y, x order";
  EXPECT_EQ(count_of(x, ">0.37 0.37 0.37</DataItem>"), 2u);
  EXPECT_EQ(count_of(x, "AttributeType=\"Scalar\" Center=\"Node\""), 2u);
  EXPECT_EQ(count_of(x, "AttributeType=\"Vector\" Center=\"Node\""), 2u);

  pbms::h5::Handle file(H5Fopen((dir / "grid.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  const std::regex ref(
      "<DataItem Dimensions=\"([0-9 ]+)\"[^>]*Format=\"HDF\">([^<:]+):([^<]+)</DataItem>");
  int refs = 0;
  for (std::sregex_iterator it(x.begin(), x.end(), ref), end; it != end; ++it, ++refs) {
    EXPECT_EQ((*it)[2].str(), "grid.h5") << "the reference must be relative";
    const std::string path = (*it)[3].str();
    ASSERT_GT(H5Lexists(file.id(), path.c_str(), H5P_DEFAULT), 0) << path;
    std::ostringstream dims;
    for (const auto d : read_dataset(file.id(), path).dims)
      dims << (dims.tellp() > 0 ? " " : "") << d;
    EXPECT_EQ(dims.str(), (*it)[1].str()) << path;
  }
  EXPECT_EQ(refs, 4);
}

// A run resumed from a checkpoint after step 10 of a file that already
// holds step 20 ends with the same file contents and the same XDMF text as
// a run never interrupted.
TEST(GridFieldWriter, ReopenedAfterAStepDropsLaterFramesAndAppends) {
  const ScratchDir scratch;
  const auto& dir = scratch.path();
  const auto grid = test_grid();
  const auto box = grid.node_box();
  const auto f = [&](int k) { return make_frame(box, k); };
  {
    GridFieldWriter w(MPI_COMM_SELF, (dir / "whole").string(), grid, box);
    for (int k = 0; k < 4; ++k) w.write_frame(10 * k, 0.5 * k, fields_of(f(k)));
  }
  {
    GridFieldWriter w(MPI_COMM_SELF, (dir / "resumed").string(), grid, box);
    for (int k = 0; k < 3; ++k) w.write_frame(10 * k, 0.5 * k, fields_of(f(k)));
  }
  {
    auto w = GridFieldWriter::reopen(MPI_COMM_SELF, (dir / "resumed").string(), grid, box, 10);
    EXPECT_EQ(w->frames(), 2);
    EXPECT_EQ(count_of(slurp(dir / "resumed.xdmf"), "<Grid Name=\"step_"), 2u);
    for (int k = 2; k < 4; ++k) w->write_frame(10 * k, 0.5 * k, fields_of(f(100 + k)));
  }
  std::string expected = slurp(dir / "whole.xdmf");
  expected = std::regex_replace(expected, std::regex("whole"), "resumed");
  EXPECT_EQ(slurp(dir / "resumed.xdmf"), expected);
  pbms::h5::Handle file(H5Fopen((dir / "resumed.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                        H5Fclose);
  // Step 20 is the resumed run's, not the dropped one's.
  EXPECT_EQ(read_dataset(file.id(), "step_20/mass").values[0], mass_at(0, 0, 0, 102));
  EXPECT_EQ(read_dataset(file.id(), "step_10/velocity").values[1], velocity_at(0, 0, 0, 1, 1));
  EXPECT_THROW((void)GridFieldWriter::reopen(MPI_COMM_SELF, (dir / "none").string(), grid, box, 10),
               pbms::Error);
}

TEST(GridFieldWriter, RefusesBadBoxesAndFields) {
  const ScratchDir scratch;
  const auto& dir = scratch.path();
  const auto base = (dir / "grid").string();
  const auto grid = test_grid();
  EXPECT_THROW(GridFieldWriter(MPI_COMM_SELF, base, grid, {{0, 0, 0}, {6, 4, 3}}), pbms::Error);
  EXPECT_THROW(GridFieldWriter(MPI_COMM_SELF, base, grid, {{0, 0, 0}, {5, 4, 2}}), pbms::Error)
      << "one rank owning part of the grid leaves nodes unwritten";
  EXPECT_THROW(GridFieldWriter(MPI_COMM_SELF, (dir / "a:b").string(), grid, grid.node_box()),
               pbms::Error);

  GridFieldWriter w(MPI_COMM_SELF, base, grid, grid.node_box());
  const auto f = make_frame(grid.node_box(), 0);
  const double* m = f.mass.data();
  EXPECT_THROW(w.write_frame(0, 0.0, {{"mass", "kg", 2, m}}), pbms::Error);
  EXPECT_THROW(w.write_frame(0, 0.0, {{"a/b", "kg", 1, m}}), pbms::Error);
  EXPECT_THROW(w.write_frame(0, 0.0, {{"", "kg", 1, m}}), pbms::Error);
  EXPECT_THROW(w.write_frame(0, 0.0, {{"mass", "kg", 1, m}, {"mass", "g", 1, m}}), pbms::Error);
  EXPECT_THROW(w.write_frame(0, 0.0, {{"mass", "kg", 1, nullptr}}), pbms::Error);
  EXPECT_THROW(w.write_frame(0, std::nan(""), {{"mass", "kg", 1, m}}), pbms::Error);
  EXPECT_EQ(w.frames(), 0);
  w.write_frame(0, 0.0, {{"mass", "kg", 1, m}});
  EXPECT_THROW(w.write_frame(0, 1.0, {{"mass", "kg", 1, m}}), pbms::Error);
  // A refused frame leaves the writer usable.
  w.write_frame(1, 1.0, {{"mass", "kg", 1, m}});
  EXPECT_EQ(w.frames(), 2);
}
