// Checkpoints and outputs under abuse (issue 30): a flipped bit or an
// impossible state in a checkpoint is bad input, one line, when it is read;
// a full disk ends the run with one line, the previous checkpoint whole and
// history.csv in step; a run restarted into another folder writes a series
// that opens there.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <vector>

#include "src/checkpoint.hpp"
#include "src/setup.hpp"
#include "src/state_setup.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

using testing::lineCount;
using testing::runLagremap;

// Sod at half resolution stopped at step 40 (exit code 3), which leaves its
// checkpoint in `dir`/run; returns the command line that continues it.
std::string stoppedSod(const std::string& dir) {
  const std::string run = "--problem sod --scale 0.5 --quiet --output " + dir + "/run";
  const auto stopped = runLagremap(run + " --set numerics.max_steps=40");
  EXPECT_EQ(stopped.exit_code, 3) << stopped.output;
  return run;
}

// Exit code 2 and one line naming the file and `what`.
void expectBadInput(const testing::CommandResult& result, const std::string& file,
                    const std::string& what) {
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_EQ(lineCount(result.error), 1) << result.error;
  EXPECT_NE(result.error.find("'" + file + "'"), std::string::npos) << result.error;
  EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

// Without checksums these restarts continued with other fields (exit code 0).
TEST(Checkpoint, AFlippedBitIsBadInputNamingTheFileAndDataset) {
  const std::string dir = testing::scratchDir("checkpoint_bit");
  const std::string run = stoppedSod(dir);
  const std::string good = dir + "/run/checkpoint.h5";
  ASSERT_EQ(runLagremap(run + " --restart " + good).exit_code, 0);
  // A mantissa bit (bit 26: a relative change of 1e-8) of a cell's energy
  // and of a node's position.
  for (const char* dataset : {"cells/E_c", "nodes/x_n"}) {
    const std::string copy = dir + "/" + std::string(dataset).substr(0, 5) + ".h5";
    std::filesystem::copy_file(good, copy);
    const std::uint64_t offset = testing::valueOffset(copy, dataset, 17);
    ASSERT_GT(offset, 0u) << dataset;
    testing::flipBit(copy, offset + 3, 2);
    expectBadInput(runLagremap(run + " --restart " + copy), copy, dataset);
  }
  // A bit of the loop's last dt (an attribute): found by its bytes, which
  // the file holds once.
  const std::string copy = dir + "/dt_prev.h5";
  std::filesystem::copy_file(good, copy);
  const hid_t file = H5Fopen(copy.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t attribute = H5Aopen(file, "dt_prev", H5P_DEFAULT);
  double dt_prev = 0.0;
  H5Aread(attribute, H5T_NATIVE_DOUBLE, &dt_prev);
  H5Aclose(attribute);
  H5Fclose(file);
  const std::string bytes = testing::readFile(copy);
  const std::string pattern(reinterpret_cast<const char*>(&dt_prev), sizeof dt_prev);
  const auto at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(pattern, at + 1), std::string::npos);
  testing::flipBit(copy, at + 3, 2);
  expectBadInput(runLagremap(run + " --restart " + copy), copy, "loop's numbers");
  std::filesystem::remove_all(dir);
}

// Sets the root `format` attribute of checkpoint `path` to "lagremap
// checkpoint 1" (the format written before the checksums) and deletes the
// checksum attributes named in `checksums` ("" for the root's, else a
// dataset's path).
void editToFormat1(const std::string& path, const std::vector<std::string>& checksums) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Adelete(file, "format");
  const std::string format = "lagremap checkpoint 1";
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, format.size());
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(file, "format", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, type, format.data());
  H5Aclose(attribute);
  H5Sclose(space);
  H5Tclose(type);
  for (const std::string& name : checksums) {
    if (name.empty()) {
      H5Adelete(file, "checksum");
    } else {
      H5Adelete_by_name(file, name.c_str(), "checksum", H5P_DEFAULT);
    }
  }
  H5Fclose(file);
}

// The datasets of a sod checkpoint, each carrying its checksum.
std::vector<std::string> checkpointDatasets(const std::string& path) {
  std::vector<std::string> names;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  // (the link's info type differs between HDF5 versions: taken as auto)
  H5Lvisit(
      file, H5_INDEX_NAME, H5_ITER_NATIVE,
      [](hid_t group, const char* name, const auto*, void* out) -> herr_t {
        const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
        if (H5Iget_type(object) == H5I_DATASET) {
          static_cast<std::vector<std::string>*>(out)->push_back(name);
        }
        H5Oclose(object);
        return 0;
      },
      &names);
  H5Fclose(file);
  return names;
}

// Checkpoints of format 1 (written without checksums) still restart.
TEST(Checkpoint, AFileOfTheFormatBeforeChecksumsStillRestarts) {
  const std::string dir = testing::scratchDir("checkpoint_format");
  const std::string run = stoppedSod(dir);
  const std::string old = dir + "/format_1.h5";
  std::filesystem::copy_file(dir + "/run/checkpoint.h5", old);
  std::vector<std::string> checksums = checkpointDatasets(old);
  ASSERT_GE(checksums.size(), 3u);
  checksums.push_back("");
  editToFormat1(old, checksums);
  const auto result = runLagremap(run + " --restart " + old);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::filesystem::remove_all(dir);
}

// A checkpoint carrying checksums is verified whatever its format attribute
// says. Before, "lagremap checkpoint 1" in that attribute turned the
// verification off and a flipped bit restarted into other results.
TEST(Checkpoint, ChecksumsAreVerifiedWhateverTheFormatAttributeSays) {
  const std::string dir = testing::scratchDir("checkpoint_format_edit");
  const std::string run = stoppedSod(dir);
  // The format attribute edited: the root's checksum no longer matches.
  const std::string edited = dir + "/edited.h5";
  std::filesystem::copy_file(dir + "/run/checkpoint.h5", edited);
  editToFormat1(edited, {});
  expectBadInput(runLagremap(run + " --restart " + edited), edited, "loop's numbers");
  // The root's checksum deleted too, and a bit of a cell's energy flipped:
  // the dataset's own checksum finds it.
  const std::string flipped = dir + "/flipped.h5";
  std::filesystem::copy_file(dir + "/run/checkpoint.h5", flipped);
  editToFormat1(flipped, {""});
  const std::uint64_t offset = testing::valueOffset(flipped, "cells/E_c", 17);
  ASSERT_GT(offset, 0u);
  testing::flipBit(flipped, offset + 3, 2);
  expectBadInput(runLagremap(run + " --restart " + flipped), flipped, "cells/E_c");
  std::filesystem::remove_all(dir);
}

// A restart continues the run of its checkpoint: a key of the physics, the
// mesh or the set-up changed is bad input naming it (before, a Johnson-Cook
// rod's checkpoint restarted under perfect plasticity, silently); t_end,
// numerics.* and check.* may change.
TEST(Checkpoint, ARestartKeepsTheRunsKeys) {
  const std::string dir = testing::scratchDir("checkpoint_keys");
  const std::string rod =
      "--problem rod --scale 0.25 --quiet --set metal.hardening=johnson_cook"
      " --set metal.jc_B=3e8 --set metal.jc_n=0.3 --output " +
      dir + "/rod";
  const auto stopped = runLagremap(rod + " --set numerics.max_steps=5");
  ASSERT_EQ(stopped.exit_code, 3) << stopped.output;
  const std::string checkpoint = dir + "/rod/checkpoint.h5";
  const std::string perfect =
      "--problem rod --scale 0.25 --quiet --set metal.hardening=perfect"
      " --set metal.jc_B=3e8 --set metal.jc_n=0.3 --output " +
      dir + "/perfect";
  const auto changed = runLagremap(perfect + " --restart " + checkpoint);
  expectBadInput(changed, checkpoint, "metal.hardening=johnson_cook");
  EXPECT_NE(changed.error.find("this run has metal.hardening=perfect"), std::string::npos)
      << changed.error;
  const auto scaled = runLagremap("--problem rod --scale 0.5 --quiet --output " + dir +
                                  "/scaled --restart " + checkpoint);
  expectBadInput(scaled, checkpoint, "mesh.nx=");
  // The loop's end, its numerics and the checks may change.
  const auto further = runLagremap(rod + " --restart " + checkpoint +
                                   " --set t_end=2e-7 --set numerics.cfl=0.3"
                                   " --set check.length_tolerance=1");
  EXPECT_EQ(further.exit_code, 0) << further.output;
  std::filesystem::remove_all(dir);
}

// A checkpoint written with a state no run reaches (a buggy writer, or a
// file edited by hand with its checksums), read back. Before, such a state
// was accepted and the run failed later with exit code 3 (here at its next
// step: a tangled cell, a time-step collapse), or ran on.
TEST(Checkpoint, AnImpossibleStateIsBadInputWhenRead) {
  const std::string dir = testing::scratchDir("checkpoint_state");
  const std::string run = stoppedSod(dir);
  const RunOptions options = testing::problemOptions("sod", {}, 0.5);
  ProblemSetup setup = setUpProblem(findProblem("sod"), options.config, "sod");
  // Reads the stopped run's checkpoint, makes `change` to its state and
  // writes it (checksums and all) to `name`.h5; restarts from that.
  auto restartChanged = [&](const std::string& name, auto change) {
    State state = allocateState(setup.mesh, false);
    initializeState(setup, state);
    LoopState loop =
        readCheckpoint(dir + "/run/checkpoint.h5", setup.mesh, state, "sod", "lagrange");
    change(state, loop);
    const std::string path = dir + "/" + name + ".h5";
    writeCheckpoint(path, setup.mesh, state, loop);
    return std::make_pair(path, runLagremap(run + " --restart " + path));
  };
  {
    const auto [path, result] = restartChanged("unchanged", [](State&, LoopState&) {});
    EXPECT_EQ(result.exit_code, 0) << result.output;
  }
  {
    const auto [path, result] = restartChanged("negative_mass", [](State& s, LoopState&) {
      Kokkos::deep_copy(Kokkos::subview(s.m_c, 7), -1.0);
    });
    expectBadInput(result, path, "cells/m_c is -1 at cell 7 (masses must be positive)");
  }
  {
    const auto [path, result] = restartChanged("nan_velocity", [](State& s, LoopState&) {
      Kokkos::deep_copy(Kokkos::subview(s.v_c, 9, 1), NAN);
    });
    expectBadInput(result, path, "cells/v_c[1] is nan at cell 9 (values must be finite)");
  }
  {
    const auto [path, result] =
        restartChanged("zero_dt", [](State&, LoopState& loop) { loop.dt_prev = 0.0; });
    expectBadInput(result, path, "impossible dt_prev = 0 at step 40");
  }
  std::filesystem::remove_all(dir);
}

// The files a series .xmf names (the part before ':' of each data item).
std::set<std::string> filesNamedBy(const std::string& xmf) {
  const std::string text = testing::readFile(xmf);
  const std::regex item("Format=\"HDF\">([^:<]+):");
  std::set<std::string> files;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), item); it != std::sregex_iterator();
       ++it) {
    files.insert((*it)[1]);
  }
  return files;
}

// Before: the restarted run's fields.xmf listed fields_00000.h5, which only
// the first folder holds, and ParaView could not open the series.
TEST(Checkpoint, ARunRestartedIntoAnotherFolderWritesASeriesThatOpensThere) {
  const std::string dir = testing::scratchDir("checkpoint_folder");
  const std::string run = stoppedSod(dir);
  const std::string checkpoint = dir + "/run/checkpoint.h5";
  const std::string elsewhere = "--problem sod --scale 0.5 --quiet --output " + dir + "/second";
  ASSERT_EQ(runLagremap(elsewhere + " --restart " + checkpoint).exit_code, 0);
  const std::set<std::string> second = filesNamedBy(dir + "/second/fields.xmf");
  EXPECT_EQ(second, std::set<std::string>{"fields_00001.h5"});
  for (const std::string& file : second) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/second/" + file)) << file;
  }
  // Restarted in its own folder, the series goes on from the first file.
  ASSERT_EQ(runLagremap(run + " --restart " + checkpoint).exit_code, 0);
  EXPECT_EQ(filesNamedBy(dir + "/run/fields.xmf"),
            (std::set<std::string>{"fields_00000.h5", "fields_00001.h5"}));
  std::filesystem::remove_all(dir);
}

// A small tmpfs mounted for one test (root only); unmounted at the end.
class SmallDisk {
 public:
  SmallDisk(const std::string& path, const std::string& size) : path_(path) {
    std::filesystem::create_directories(path);
    mounted_ = ::geteuid() == 0 &&
               ::mount("tmpfs", path.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) ::umount(path_.c_str());
  }
  bool mounted() const { return mounted_; }

 private:
  std::string path_;
  bool mounted_ = false;
};

// Sedov at 32^3 writes a 5.3 MB snapshot and 2.7 MB checkpoints: on a 9 MB
// disk the second checkpoint finds no room to start, on 10 and 11 MB it
// fills the disk half way. Before: HDF5's error dump, "infinite loop
// closing library" (or a crash at exit), the half-written checkpoint.h5.tmp
// left, and history.csv empty.
TEST(Checkpoint, AFullDiskEndsTheRunWithOneLineAndTheRecordInStep) {
  const std::string dir = testing::scratchDir("checkpoint_disk");
  for (const char* size : {"9m", "10m", "11m"}) {
    const std::string disk = dir + "/disk" + size;
    SmallDisk small(disk, size);
    if (!small.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
    const auto result = runLagremap("--problem sedov --quiet --checkpoint-every 2 --output " +
                                    disk + " --set numerics.max_steps=6");
    EXPECT_EQ(result.exit_code, 3) << size << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << size << result.error;
    EXPECT_NE(result.error.find("checkpoint.h5.tmp"), std::string::npos) << result.error;
    EXPECT_NE(result.error.find("No space left on device"), std::string::npos) << result.error;
    // The first checkpoint (step 2) whole, nothing half-written left.
    for (const auto& entry : std::filesystem::directory_iterator(disk)) {
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
    const auto restarted =
        runLagremap("--problem sedov --quiet --output " + dir + "/restarted" +
                    " --set numerics.max_steps=3 --restart " + disk + "/checkpoint.h5");
    EXPECT_EQ(restarted.exit_code, 3) << restarted.output;  // (at max_steps)
    EXPECT_NE(restarted.error.find("step 3: numerics.max_steps"), std::string::npos)
        << restarted.error;
    // history.csv: the header, the initial state and steps 1 to 4, whole lines.
    const std::string history = testing::readFile(disk + "/history.csv");
    EXPECT_EQ(lineCount(history), 6) << history;
    ASSERT_EQ(history.back(), '\n');
    EXPECT_EQ(history.compare(history.rfind('\n', history.size() - 2) + 1, 2, "4,"), 0) << history;
  }
  std::filesystem::remove_all(dir);
}

// The snapshots' `plastic_strain` is the cells' mass average of their
// materials' eps_p (FinalFields::plasticStrain): read back from the last
// snapshot of a short hardening rod, in both modes (remap: mixed cells of
// copper and air), it is the run's final field value for value, and zero in
// the first snapshot.
TEST(Snapshots, PlasticStrainIsWrittenAsTheCellsMassAverage) {
  const std::string dir = testing::scratchDir("plastic_strain");
  for (const char* mode : {"lagrange", "remap"}) {
    RunOptions options = testing::coarseRodOptions(mode, "4e-6");
    options.write_files = true;
    options.output_dir = dir + "/" + mode;
    const RunResult result = runProblem(options);
    ASSERT_FALSE(result.failed) << mode << ": " << result.failure;
    const auto first =
        testing::readDoubles(options.output_dir + "/fields_00000.h5", "/fields/plastic_strain");
    const auto last =
        testing::readDoubles(options.output_dir + "/fields_00001.h5", "/fields/plastic_strain");
    const Index cells = Index(result.fields.x_c.extent(0));
    ASSERT_EQ(Index(first.size()), cells) << mode;
    ASSERT_EQ(Index(last.size()), cells) << mode;
    double largest = 0.0;
    int mixed_and_strained = 0;
    for (Index c = 0; c < cells; ++c) {
      EXPECT_EQ(first[std::size_t(c)], 0.0) << mode << " cell " << c;
      EXPECT_EQ(last[std::size_t(c)], result.fields.plasticStrain(c)) << mode << " cell " << c;
      largest = std::max(largest, last[std::size_t(c)]);
      const double alpha = result.fields.alpha(c, 0);
      if (alpha > 0.0 && alpha < 1.0 && last[std::size_t(c)] > 0.0) ++mixed_and_strained;
    }
    EXPECT_GT(largest, 0.02) << mode;
    if (std::string(mode) == "remap") {
      EXPECT_GT(mixed_and_strained, 0);
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lagremap
