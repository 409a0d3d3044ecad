// The small valid beam campaign that config and CLI tests edit line by line (the README's
// walk-through and docs/config.md show the same lines).
#pragma once

#include <string>

namespace sb::test {

inline const std::string kSmallBeamConfig = R"(
[campaign]
name = "t"

[structure]
kind = "beam"

[structure.beam]
length_m = 0.5
width_m = 0.05
thickness_m = 0.003
density_kg_m3 = 2700.0
youngs_modulus_pa = 70e9

[structure.beam.supports.root]
x_m = 0.0
kind = "clamped"

[structure.beam.points]
shaker = 0.1
tip = 0.5

[[structure.beam.masses]]
point = "tip"
mass_kg = 0.01

[structure.excitation]
point = "shaker"
)";

}  // namespace sb::test
