// shakerbench-config-docs: keeps the key tables of docs/config.md equal to the declarations.
// `--check FILE` exits 1 when a table differs, is missing or names no declared table;
// `--write FILE` rewrites every `<!-- keys [TABLE] -->` block from the declarations.
#include <iostream>
#include <string>
#include <vector>

#include "bench/config_schema.hpp"
#include "config/reference.hpp"
#include "core/text_file.hpp"

int main(int argc, char** argv) {
    const std::string usage = "usage: shakerbench-config-docs --check|--write docs/config.md";
    if (argc != 3) {
        std::cerr << usage << '\n';
        return 2;
    }
    const std::string mode = argv[1];
    const std::string file = argv[2];
    if (mode != "--check" && mode != "--write") {
        std::cerr << usage << '\n';
        return 2;
    }
    try {
        const std::string text = sb::read_text_file(file);
        std::vector<std::string> problems;
        const std::string updated =
            sb::config::update_key_blocks(text, sb::bench::campaign_schema(), problems);
        for (const auto& p : problems) std::cerr << file << ": " << p << '\n';
        if (mode == "--write") {
            if (updated != text) sb::write_file_atomically(file, updated);
            return problems.empty() ? 0 : 1;
        }
        if (updated != text) {
            std::cerr << file << ": the key tables differ from the declarations; run "
                      << "shakerbench-config-docs --write " << file << '\n';
        }
        return problems.empty() && updated == text ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench-config-docs: " << e.what() << '\n';
        return 2;
    }
}
