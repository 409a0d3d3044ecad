// Entry point of every test executable: each test process gets its own temporary directory
// (TMPDIR), so that suites writing fixed file names under temp_directory_path() never collide
// when CTest runs tests in parallel, or when several checkouts test on one machine.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("sb-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    ::setenv("TMPDIR", dir.c_str(), 1);
    testing::InitGoogleTest(&argc, argv);
    const int status = RUN_ALL_TESTS();
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    return status;
}
