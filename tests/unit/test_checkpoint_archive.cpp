#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/io/checkpoint_archive.hpp"

using pbms::CheckpointArchive;
namespace fs = std::filesystem;

namespace {

const std::string kStage = "stage 'pull' (dpd_run), parameters 00000000000000ab";

fs::path scratch_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pbms_ckpt_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string refusal(const fs::path& file, const std::string& identity) {
  try {
    (void)CheckpointArchive::read(file, identity, MPI_COMM_SELF);
  } catch (const pbms::Error& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST(CheckpointArchive, ReadsBackEveryArrayBitForBit) {
  const fs::path file = scratch_file("round_trip.h5");
  CheckpointArchive a;
  a.put("engine/particles", {1.0, -2.5e-300, 0.1 + 0.2});
  a.put("engine/step", 800.0);
  a.put("probes/empty", std::vector<double>{});
  std::string restart("LAMMPS\0\x01\xff restart", 17);
  a.put_bytes("lammps/restart", restart);
  a.put_bytes("lammps/empty", "");
  a.write(file, kStage + "; PBMS 0.1.0 (abc)");
  EXPECT_FALSE(fs::exists(file.string() + ".partial"));
  const CheckpointArchive b =
      CheckpointArchive::read(file, kStage + "; PBMS 0.1.0 (abc)", MPI_COMM_SELF);
  EXPECT_EQ(b.get("engine/particles"), (std::vector<double>{1.0, -2.5e-300, 0.1 + 0.2}));
  EXPECT_EQ(b.scalar("engine/step"), 800.0);
  EXPECT_TRUE(b.has("probes/empty"));
  EXPECT_TRUE(b.get("probes/empty").empty());
  EXPECT_THROW((void)b.get("tension/strain"), pbms::Error);
  EXPECT_EQ(b.bytes("lammps/restart"), restart);
  EXPECT_EQ(b.bytes("lammps/empty"), "");
  EXPECT_FALSE(b.has("lammps/restart"));  // bytes are not an array
  EXPECT_THROW((void)b.bytes("engine/step"), pbms::Error);
  fs::remove(file);
}

// Another commit's checkpoint of the same stage names the versions; another
// stage's names the stages, not the versions that agree.
TEST(CheckpointArchive, RefusesAnotherIdentityNamingWhatDiffers) {
  const fs::path file = scratch_file("identity.h5");
  CheckpointArchive a;
  a.put("engine/step", 1.0);
  a.write(file, kStage + "; PBMS 0.1.0 (abc)");
  const std::string version = refusal(file, kStage + "; PBMS 0.1.0 (def)");
  EXPECT_NE(version.find("it holds the state of PBMS 0.1.0 (abc); this run is PBMS 0.1.0 (def)"),
            std::string::npos)
      << version;
  const std::string stage =
      refusal(file, "stage 'pull' (dpd_run), parameters 00000000000000cd; PBMS 0.1.0 (abc)");
  EXPECT_NE(stage.find("parameters 00000000000000ab; this run is stage 'pull' (dpd_run), "
                       "parameters 00000000000000cd"),
            std::string::npos)
      << stage;
  EXPECT_EQ(stage.find("PBMS"), std::string::npos) << stage;
  fs::remove(file);
}
