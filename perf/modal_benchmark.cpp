// The modal analysis of a meshed beam: the dense generalised eigensolver against shift-invert
// Lanczos on sparse factors (structure/lowest_modes.hpp), side by side in one run
// (docs/performance.md). Every campaign, prediction and calibration evaluation solves it once
// per model it builds.
#include <benchmark/benchmark.h>

#include <Eigen/Eigenvalues>
#include <string>

#include "bench/campaign_config.hpp"
#include "structure/linear_model.hpp"
#include "structure/lowest_modes.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::structure {
namespace {

/// The shipped H-0 campaign's beam (configs/paper000-h0.toml), with `elements` elements.
LinearModel paper000_beam(int elements) {
    auto config =
        bench::load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    config.structure.beam.min_elements = elements;
    return build_linear_model(config.structure, SB_SOURCE_DIR);
}

void BM_DenseSolver(benchmark::State& st) {
    const LinearModel model = paper000_beam(static_cast<int>(st.range(0)));
    for (auto _ : st) {
        const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness(),
                                                                               model.mass());
        benchmark::DoNotOptimize(solver.eigenvalues().data());
    }
    st.counters["dofs"] = model.dofs();
}

void BM_Lanczos(benchmark::State& st) {
    const LinearModel model = paper000_beam(static_cast<int>(st.range(0)));
    for (auto _ : st) {
        const auto pairs = lowest_eigenpairs(model.stiffness(), model.mass(), 6);
        if (!pairs) st.SkipWithError("left to the dense solver");
        benchmark::DoNotOptimize(pairs);
    }
    st.counters["dofs"] = model.dofs();
}

void BM_ComputeModes(benchmark::State& st) {
    const LinearModel model = paper000_beam(static_cast<int>(st.range(0)));
    for (auto _ : st) {
        const ModalBasis basis = compute_modes(model, DampingSpec{}, 6);
        benchmark::DoNotOptimize(basis.shapes.data());
    }
}

// 60 elements: the shipped configs' mesh.
BENCHMARK(BM_DenseSolver)->Arg(30)->Arg(60)->Arg(120)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lanczos)->Arg(30)->Arg(60)->Arg(120)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ComputeModes)->Arg(60)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sb::structure

BENCHMARK_MAIN();
