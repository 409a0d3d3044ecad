// The reduced modal model steps without touching the heap: it runs at the DEM time step, so an
// allocation per step would cost more than the step itself. The test counts malloc calls
// (Eigen and operator new both end in malloc) by interposing glibc's malloc in this
// executable; sanitizer builds replace malloc themselves, so there the count is skipped.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>

#include "beam_fixtures.hpp"
#include "structure/reduced_modal_model.hpp"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SB_COUNT_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SB_COUNT_MALLOC 0
#endif
#endif
#ifndef SB_COUNT_MALLOC
#define SB_COUNT_MALLOC 1
#endif

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_mallocs{0};
}  // namespace

#if SB_COUNT_MALLOC
extern "C" void* __libc_malloc(std::size_t size);  // glibc's own allocator
extern "C" void* malloc(std::size_t size) {
    if (g_counting.load(std::memory_order_relaxed)) g_mallocs.fetch_add(1);
    return __libc_malloc(size);
}
#endif

namespace sb::structure {
namespace {

TEST(ReducedModalModelHeap, SteppingWithPointLoadsAndBaseMotionAllocatesNothing) {
    if (!SB_COUNT_MALLOC) GTEST_SKIP() << "malloc is the sanitizer's in this build";
    StructureSpec spec = testing::paper000_loaded();
    spec.excitation.kind = ExcitationSpec::Kind::base;
    spec.excitation.support = "root";
    const LinearModel model = build_linear_model(spec, {});
    const ModalBasis basis = compute_modes(model, spec.damping, 8);
    ReducedModalModel sim(model, basis, 1e-4);
    const int damper = sim.point_index("damper");
    const int shaker = sim.point_index("shaker");
    double sink = 0.0;
    g_mallocs = 0;
    g_counting = true;
    for (int n = 0; n < 1000; ++n) {
        const double t = 1e-4 * n;
        sim.set_point_load(damper, {0.0, 0.0, 0.1 * t}, {0.01 * t, 0.0, 0.0});
        sim.set_point_load("shaker", {0.0, 0.0, -0.1 * t}, Eigen::Vector3d::Zero());
        sim.set_base_motion(1e-3 * t, 1e-3, 0.0);
        sim.step();
        sink += sim.displacement(damper).z() + sim.velocity(damper).z() +
                sim.acceleration(shaker).z() + sim.rotation(damper).y() +
                sim.angular_velocity(damper).y() + sim.angular_acceleration(damper).y();
    }
    g_counting = false;
    EXPECT_EQ(g_mallocs.load(), 0);
    EXPECT_TRUE(std::isfinite(sink));
}

TEST(ReducedModalModelHeap, TheCounterSeesAnEigenAllocation) {
    // Guards the test above against a counter that never counts.
    if (!SB_COUNT_MALLOC) GTEST_SKIP() << "malloc is the sanitizer's in this build";
    g_mallocs = 0;
    g_counting = true;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(64);
    g_counting = false;
    EXPECT_GE(g_mallocs.load(), 1);
    EXPECT_NE(v.data(), nullptr);
}

}  // namespace
}  // namespace sb::structure
