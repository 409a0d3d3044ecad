// The declarations of the config, table by table (bench/config_schema.cpp puts them together).
#pragma once

#include <memory>

#include "config/schema.hpp"

namespace sb::bench::schema {

/// [structure] and everything below it, bound to structure::StructureSpec.
std::shared_ptr<const config::Table> structure_table();

/// [dampers.NAME] and everything below it, bound to DamperSpec.
std::shared_ptr<const config::Table> damper_table();

}  // namespace sb::bench::schema
