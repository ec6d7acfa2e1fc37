#include <gtest/gtest.h>

#include <cstdlib>

#include <filesystem>

#include "pbms/io/h5md_writer.hpp"
#include "pbms/progress_meter.hpp"
#include "postmortem.hpp"

TEST(ProgressMeter, LogModePrintsEachTenthOnce) {
  pbms::ProgressMeter m("s", false);
  int lines = 0;
  for (int step = 0; step <= 1000; step += 5) {
    if (m.update(step, 1000, step * 0.002, "", step * 0.01)) ++lines;
  }
  EXPECT_EQ(lines, 11);  // 0 %, 10 %, ..., 100 %
}

TEST(ProgressMeter, RateAndEta) {
  pbms::ProgressMeter m("iso", true);
  m.update(0, 1000, 0.0, "", 0.0);
  const auto line = m.format(250, 1000, 0.5, "P = 0 GPa", 5.0);
  EXPECT_NE(line.find("step 250/1000"), std::string::npos) << line;
  EXPECT_NE(line.find("50 steps/s"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 15s"), std::string::npos) << line;
  EXPECT_NE(line.find("0.50 ps"), std::string::npos) << line;
  EXPECT_EQ(pbms::format_duration(3725), "1h02m");
}

// A stage whose first report comes at step 5,000, 0.04 s after the meter
// started, once showed 137,508 steps/s: the rate counts from the first
// report's step, and not before half a second has passed.
TEST(ProgressMeter, RateCountsFromTheFirstReport) {
  pbms::ProgressMeter m("run", true);
  m.update(5000, 100000, -1.0, "", 10.0);
  EXPECT_NE(m.format(5500, 100000, -1.0, "", 10.04).find("- steps/s"), std::string::npos);
  const auto line = m.format(7000, 100000, -1.0, "", 12.0);
  EXPECT_NE(line.find("1000 steps/s"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 1m33s"), std::string::npos) << line;
}

TEST(Postmortem, ParsesOpenMpiReports) {
  const auto killed = pbms::coupler::parse_mpirun_output(
      "--------\nmpirun noticed that process rank 2 with PID 4242 on node vm exited on signal 9 "
      "(Killed).\n--------\n");
  EXPECT_EQ(killed.world_rank, 2);
  EXPECT_EQ(killed.signal, 9);
  EXPECT_EQ(killed.signal_name, "Killed");
  const auto exited = pbms::coupler::parse_mpirun_output(
      "mpirun detected that one or more processes exited with non-zero status...\n\n"
      "  Process name: [[29841,1],1]\n  Exit code:    3\n");
  EXPECT_EQ(exited.world_rank, 1);
  EXPECT_EQ(exited.exit_code, 3);
  EXPECT_EQ(pbms::coupler::parse_mpirun_output("nothing").world_rank, -1);
}

TEST(H5md, WritesReadableTrajectory) {
  const auto path = (std::filesystem::temp_directory_path() / "pbms_unit_traj.h5md").string();
  {
    pbms::H5mdWriter::Options opt;
    opt.path = path;
    opt.velocities = true;
    pbms::H5mdWriter w(MPI_COMM_SELF, opt, {1, 2}, {0, 0});
    w.write_frame(0, 0.0, {10, 10, 10}, {1, 2}, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 0, 0, 0});
    w.write_frame(10, 0.02, {10, 10, 10.5}, {1, 2}, {0.1, 0, 0, 1, 1.1, 1}, {1, 0, 0, 0, 1, 0});
    EXPECT_EQ(w.frames(), 2);
  }
  pbms::h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  pbms::h5::Handle ds(H5Dopen2(f.id(), "particles/all/position/value", H5P_DEFAULT), H5Dclose);
  pbms::h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
  hsize_t dims[3];
  ASSERT_EQ(H5Sget_simple_extent_ndims(space.id()), 3);
  H5Sget_simple_extent_dims(space.id(), dims, nullptr);
  EXPECT_EQ(dims[0], 2u);
  EXPECT_EQ(dims[1], 2u);
  EXPECT_EQ(dims[2], 3u);
  double x[12];
  H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, x);
  EXPECT_DOUBLE_EQ(x[6], 0.1);
  EXPECT_DOUBLE_EQ(x[10], 1.1);
  EXPECT_GT(H5Aexists_by_name(f.id(), "h5md", "version", H5P_DEFAULT), 0);
  EXPECT_GT(H5Lexists(f.id(), "particles/all/box/edges/value", H5P_DEFAULT), 0);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // ctest runs each test in a process of its own, a singleton that needs no
  // network: Open MPI's UCX layer would take 0.22 s of its 0.35 s start,
  // over the suite's 400 tests 90 s. (gtest_discover_tests splits an
  // ENVIRONMENT list, so it is set here.)
  setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
  MPI_Init(&argc, &argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
