// Fuzz target: a Universal File Format file (datasets 58 and 58b, other datasets skipped), as
// `shakerbench identify FILE.uff` reads it. A clean end is the records or
// identification::FileError; every record must hold as many ordinates as abscissas, all finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "identification/file_error.hpp"
#include "identification/uff58.hpp"
#include "scratch.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = sb::fuzz::scratch_dir() / "f.uff";
    sb::fuzz::write_bytes(file, {reinterpret_cast<const char*>(data), size});
    std::vector<sb::identification::Uff58Record> records;
    try {
        records = sb::identification::read_uff58(file);
    } catch (const sb::identification::FileError&) {
        return 0;
    }
    for (const auto& r : records) {
        if (r.x.size() != r.y.size()) {
            std::fprintf(stderr, "uff58: %zu abscissas, %zu ordinates\n", r.x.size(), r.y.size());
            std::abort();
        }
        for (std::size_t i = 0; i < r.x.size(); ++i) {
            if (!std::isfinite(r.x[i]) || !std::isfinite(r.y[i].real()) ||
                !std::isfinite(r.y[i].imag())) {
                std::fprintf(stderr, "uff58: value %zu is not finite\n", i);
                std::abort();
            }
        }
    }
    return 0;
}
