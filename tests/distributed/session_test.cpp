// The session without a launcher: a world of one; a build without MPI started as several
// ranks refuses to run instead of running the whole campaign on each.
#include "distributed/session.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sb::distributed {
namespace {

TEST(Session, WithoutALauncherAProcessIsAWorldOfOne) {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS",
                             "PMIX_RANK", "PMI_RANK"}) {
        ASSERT_EQ(std::getenv(name), nullptr) << name << " is set: run this test without mpirun";
    }
    Session session;
    EXPECT_EQ(session.rank(), 0);
    EXPECT_EQ(session.size(), 1);
    EXPECT_EQ(session.transport(), nullptr);
    EXPECT_NE(session.describe().find("rank 0 of 1: pid "), std::string::npos);
}

TEST(Session, ABuildWithoutMpiStartedAsSeveralRanksRefusesToRun) {
    if (Session::built_with_mpi()) GTEST_SKIP() << "this build has MPI";
    ASSERT_EQ(setenv("OMPI_COMM_WORLD_SIZE", "2", 1), 0);
    try {
        Session session;
        ADD_FAILURE() << "a session of a build without MPI started as 2 ranks";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("built without MPI"), std::string::npos) << e.what();
    }
    unsetenv("OMPI_COMM_WORLD_SIZE");
}

}  // namespace
}  // namespace sb::distributed
