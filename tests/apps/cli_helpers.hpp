// Running the shakerbench executable from tests: exit code and everything it printed.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sb::test {

struct Result {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

/// Runs a shell command, stdout and stderr together.
inline Result run_command(const std::string& command) {
    Result result;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
        result.output += buffer.data();
    }
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// `shakerbench ARGS`.
inline Result run(const std::string& arguments) {
    return run_command(std::string(SB_CLI) + " " + arguments + " 2>&1");
}

inline std::filesystem::path temp_dir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("shakerbench-cli-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string file_text(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// A characterisation file's text without its command line (it names the output folder).
inline std::string without_command(const std::string& text) {
    std::istringstream in(text);
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("# command = ", 0) != 0) kept += line + "\n";
    }
    return kept;
}

inline std::string characterization_without_command(const std::filesystem::path& dir) {
    return without_command(file_text(dir / "characterization.csv"));
}

}  // namespace sb::test
