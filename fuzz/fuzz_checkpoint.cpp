// Fuzz target: a sweep checkpoint (checkpoints/<sweep>.txt), as a resumed run reads it. Each
// input is read twice: as it is (its last line must be the checksum of the rest, which almost
// no mutation keeps) and with the checksum of its content put right, so that the reader behind
// the checksum is exercised too. A clean end is a checkpoint or bench::CheckpointError; what is
// read must write back to text that reads to the same checkpoint.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "bench/sweep_checkpoint.hpp"

namespace {

void read(const std::string& text) {
    sb::bench::SweepCheckpoint checkpoint;
    try {
        checkpoint = sb::bench::parse_checkpoint(text, "fuzz.txt");
    } catch (const sb::bench::CheckpointError&) {
        return;
    }
    const std::string written = sb::bench::serialize_checkpoint(checkpoint);
    try {
        if (sb::bench::serialize_checkpoint(sb::bench::parse_checkpoint(written, "again.txt")) ==
            written) {
            return;
        }
        std::fprintf(stderr, "a checkpoint does not read back to itself:\n%s\n", written.c_str());
    } catch (const sb::bench::CheckpointError& e) {
        std::fprintf(stderr, "a written checkpoint does not read back: %s\n%s\n", e.what(),
                     written.c_str());
    }
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    read(input);
    read(sb::bench::seal_checkpoint(sb::bench::checkpoint_content(input)));
    return 0;
}
