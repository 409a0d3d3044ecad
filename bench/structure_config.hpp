// Reading the [structure] section of a campaign config into structure::StructureSpec.
#pragma once

#include <filesystem>

#include "bench/config_reader.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// Reads [structure] (keys in docs/config.md), validates it with the structure module's own
/// checks and reports everything into the section's diagnostics. Relative file names are
/// taken from `base_dir`.
structure::StructureSpec read_structure(Section structure, const std::filesystem::path& base_dir);

}  // namespace sb::bench
