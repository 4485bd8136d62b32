// Launcher detection: a process started by a PMIx launcher (Slurm's srun sets PMIX_RANK, not Open
// MPI's OMPI_COMM_WORLD_SIZE) must join the MPI world too. Open MPI's mpirun is itself a PMIx
// launcher, so the test runs it with OMPI_COMM_WORLD_SIZE removed from each rank's environment:
// what is left is what srun gives. Without detection each rank would render the whole image alone
// and say "1 rank".
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>

#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::runShell;
using tyndall::test::runTyndall;

const std::string kSmall = "--size 40x30 --photons 300 --gpu off --passes 5 -q";

std::string out(const std::string& name) { return tyndall::test::outputDir() + "/mpi_launcher_" + name; }

TEST(MpiLauncher, PmixOnlyEnvironmentJoinsTheWorld) {
    if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not installed (openmpi-bin)";
    const std::string single = out("single.exr"), two = out("pmix.exr");
    std::remove(two.c_str());
    ASSERT_EQ(runTyndall("render " + kSmall + " -o " + single).exitCode, 0);
    auto r = runShell("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                      "mpirun -np 2 --oversubscribe env -u OMPI_COMM_WORLD_SIZE " +
                      std::string(TYNDALL_BINARY) + " render " + kSmall + " --threads 1 -o " + two + " 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 ranks"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "only rank 0 prints:\n" << r.output;
    EXPECT_EQ(tyndall::readImageAttribute(two, "tyndall:ranks"), "2");
    EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(two), tyndall::readImage(single)))
        << "the PMIx-launched render is not the single-process one";
}

}  // namespace
