// Fuzz target: the sealed texts a resumed run reads back: a sweep checkpoint
// (checkpoints/<sweep>.txt), a pour's progress (settled/<bed>.settling.txt) and a
// characterisation run's progress (results/<run>.progress.txt). Each input is read twice by
// each reader: as it is (its last line must be the checksum of the rest, which almost no
// mutation keeps) and with the checksum of its content put right, so that the reader behind
// the checksum is exercised too. A clean end is the value or bench::CheckpointError; what is
// read must write back to text that reads to the same value.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "bench/characterization_progress.hpp"
#include "bench/sweep_checkpoint.hpp"

namespace {

/// Reads `text` with `parse`; what it reads must write back (`write`) to text that reads to
/// the same text again.
template <class Parse, class Write>
void read(const std::string& text, const char* kind, Parse parse, Write write) {
    std::string written;
    try {
        written = write(parse(text, "fuzz.txt"));
    } catch (const sb::bench::CheckpointError&) {
        return;
    }
    try {
        if (write(parse(written, "again.txt")) == written) return;
        std::fprintf(stderr, "a %s does not read back to itself:\n%s\n", kind, written.c_str());
    } catch (const sb::bench::CheckpointError& e) {
        std::fprintf(stderr, "a written %s does not read back: %s\n%s\n", kind, e.what(),
                     written.c_str());
    }
    std::abort();
}

void read_every_kind(const std::string& text) {
    using namespace sb::bench;
    read(text, "checkpoint", parse_checkpoint,
         [](const SweepCheckpoint& c) { return serialize_checkpoint(c); });
    read(text, "pour progress", parse_pour_progress,
         [](const sb::dem::PourProgress& p) { return serialize_pour_progress(p); });
    read(text, "run progress", parse_run_progress,
         [](const RunProgress& p) { return serialize_run_progress(p); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    read_every_kind(input);
    read_every_kind(sb::bench::seal_checkpoint(sb::bench::checkpoint_content(input)));
    return 0;
}
